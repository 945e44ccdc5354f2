// main.cpp - entry point of the facet command-line tool.
#include <cstdio>

int main() {
  std::fputs("facet: the command-line tool is being assembled\n", stderr);
  return 2;
}
