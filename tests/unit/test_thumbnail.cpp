// test_thumbnail.cpp - the freedesktop thumbnailer: URIs, the filled square, its metadata, errors, and the MIME lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/thumbnail.hpp"
#include "facet/view_spec.hpp"
#include "support/scratch_dir.hpp"

namespace facet::thumbnail_tests {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The tEXt chunks of a PNG file, keyword to text, read from its chunk list.
std::map<std::string, std::string> png_text(const fs::path& path) {
  const std::string data = read_text(path);
  std::map<std::string, std::string> out;
  std::size_t at = 8;
  while (at + 12 <= data.size()) {
    const auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<unsigned char>(data[i])); };
    const std::uint32_t length = byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3);
    const std::string type = data.substr(at + 4, 4), body = data.substr(at + 8, length);
    if (type == "tEXt") {
      const std::size_t nul = body.find('\0');
      out[body.substr(0, nul)] = body.substr(nul + 1);
    }
    at += 12 + length;
  }
  return out;
}

// An L-shaped model, long and flat, which a sphere's framing leaves small.
fs::path write_plank(const fs::path& folder) {
  const fs::path path = folder / "plank model.obj";
  std::ofstream(path) << "v 0 0 0\nv 4 0 0\nv 4 0.5 0\nv 0 0.5 0\nv 0 0 0.3\nv 4 0 0.3\nv 4 0.5 0.3\nv 0 0.5 0.3\n"
                         "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";
  return path;
}

TEST(Thumbnail, PathOfUriDecodesLocalFileUris) {
  EXPECT_EQ(path_of_uri("file:///tmp/a%20b%23c.obj"), fs::path("/tmp/a b#c.obj"));
  EXPECT_EQ(path_of_uri("file://localhost/x/y.glb"), fs::path("/x/y.glb"));
  EXPECT_EQ(path_of_uri("FILE:/x/%C3%A9.ply"), fs::path("/x/\xC3\xA9.ply"));
  EXPECT_EQ(path_of_uri("/plain/path with:colon.obj"), fs::path("/plain/path with:colon.obj"));
  EXPECT_EQ(path_of_uri("relative/model.stl"), fs::path("relative/model.stl"));
}

TEST(Thumbnail, PathOfUriRefusesWhatIsNotALocalFile) {
  for (const char* uri : {"smb://server/share/m.obj", "https://example.com/m.glb", "file://server/m.obj",
                          "file:///a%2", "file:///a%zzb.obj", "file:///a%00b.obj", "file:relative.obj"}) {
    SCOPED_TRACE(uri);
    EXPECT_THROW(path_of_uri(uri), InputError);
  }
}

TEST(Thumbnail, FileUriEscapesAndRoundTrips) {
  EXPECT_EQ(file_uri("/tmp/a b#c%d.obj"), "file:///tmp/a%20b%23c%25d.obj");
  EXPECT_EQ(file_uri("/m/x_(1)+y=z@h:~.glb"), "file:///m/x_(1)+y=z@h:~.glb");
  for (const fs::path& path : {fs::path("/tmp/\xC3\xA9t\xC3\xA9 ?.obj"), fs::path("/a/[b]/\"c\".ply")})
    EXPECT_EQ(path_of_uri(file_uri(path)), path);
  EXPECT_EQ(path_of_uri(file_uri("rel/m.obj")), fs::absolute("rel/m.obj"));
}

TEST(Thumbnail, FillImageCentresAndSpansTheTighterAxis) {
  const std::vector<glm::vec3> points{{0, 0, 0}, {4, 0, 0}, {4, 0.5f, 0}, {0, 0.5f, 0.3f}};
  Framing framing;
  framing.center = {2, 0.25f, 0.15f};
  framing.radius = 2.1f;
  const View view = fill_image(make_view(CameraSpec{}, framing, 1.0f), points);
  glm::vec2 low(1e9f), high(-1e9f);
  for (const glm::vec3& p : points) {
    const glm::vec4 clip = view.clip_from_view * view.view_from_world * glm::vec4(p, 1.0f);
    low = glm::min(low, glm::vec2(clip) / clip.w);
    high = glm::max(high, glm::vec2(clip) / clip.w);
  }
  EXPECT_NEAR(std::max(high.x - low.x, high.y - low.y), 2.0f * kFillExtent, 1e-4f);
  EXPECT_NEAR(low.x + high.x, 0.0f, 1e-4f);
  EXPECT_NEAR(low.y + high.y, 0.0f, 1e-4f);
}

TEST(Thumbnail, DrawsAFilledTransparentSquareWithItsMetadata) {
  const fs::path folder = test::scratch_dir("thumbnail");
  const fs::path model = write_plank(folder);
  Renderer renderer(1);
  ThumbnailJob job;
  job.input = model.string();
  job.output = folder / "thumb.png";
  job.size = 96;
  render_thumbnail(job, renderer);
  int width = 0, height = 0;
  const std::vector<std::uint8_t> rgba = read_png(job.output, width, height);
  ASSERT_EQ(width, 96);
  ASSERT_EQ(height, 96);
  int low_x = width, high_x = -1, low_y = height, high_y = -1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (rgba[4 * static_cast<std::size_t>(y * width + x) + 3] > 0) {
        low_x = std::min(low_x, x), high_x = std::max(high_x, x);
        low_y = std::min(low_y, y), high_y = std::max(high_y, y);
      }
  EXPECT_EQ(rgba[3], 0) << "the background is transparent";
  // kFillExtent of the wider axis, give or take the anti-aliased edge pixels; centred.
  EXPECT_NEAR(std::max(high_x - low_x, high_y - low_y) + 1, kFillExtent * 96, 2.0);
  EXPECT_NEAR(low_x + high_x, 95, 2);
  EXPECT_NEAR(low_y + high_y, 95, 2);

  const std::map<std::string, std::string> text = png_text(job.output);
  EXPECT_EQ(text.at("Thumb::URI"), file_uri(model));
  EXPECT_EQ(text.at("Thumb::URI").find(' '), std::string::npos);
  EXPECT_EQ(text.at("Thumb::Size"), std::to_string(fs::file_size(model)));
  const auto since_epoch = std::chrono::duration_cast<std::chrono::seconds>(
      std::chrono::file_clock::to_sys(fs::last_write_time(model)).time_since_epoch());
  EXPECT_EQ(text.at("Thumb::MTime"), std::to_string(since_epoch.count()));

  // A URI input is written back as given: the file manager looks its thumbnail up by that string.
  job.input = "file://localhost" + file_uri(model).substr(7);
  render_thumbnail(job, renderer);
  EXPECT_EQ(png_text(job.output).at("Thumb::URI"), job.input);
}

TEST(Thumbnail, RefusesWithoutWritingAnything) {
  const fs::path folder = test::scratch_dir("thumbnail");
  const fs::path model = write_plank(folder);
  Renderer renderer(1);
  ThumbnailJob job;
  job.output = folder / "thumb.png";
  job.input = (folder / "missing.obj").string();
  EXPECT_THROW(render_thumbnail(job, renderer), InputError);
  job.input = folder.string();
  EXPECT_THROW(render_thumbnail(job, renderer), InputError);
  job.input = model.string();
  job.max_input_bytes = 100;
  try {
    render_thumbnail(job, renderer);
    ADD_FAILURE() << "a file over the limit was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over the thumbnail limit of 100"), std::string::npos) << e.what();
  }
  job.max_input_bytes = kDefaultThumbnailInputBytes;
  for (const int size : {0, kMaxThumbnailSize + 1}) {
    job.size = size;
    EXPECT_THROW(render_thumbnail(job, renderer), std::invalid_argument);
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1) << "only the model is there";
}

TEST(Thumbnail, PngTextFollowsPngsRules) {
  const fs::path folder = test::scratch_dir("thumbnail");
  const std::vector<std::uint8_t> pixel{1, 2, 3, 4};
  for (const PngText& bad : {PngText{"", "x"}, PngText{" lead", "x"}, PngText{"a  b", "x"},
                             PngText{std::string(80, 'k'), "x"}, PngText{"ok", std::string("a\0b", 3)}}) {
    const std::vector<PngText> text{bad};
    EXPECT_THROW(write_png(folder / "bad.png", 1, 1, pixel, true, 1, text), std::invalid_argument);
  }
  EXPECT_FALSE(fs::exists(folder / "bad.png"));
}

// The MIME types of the thumbnailer entry and of facet's shared-mime-info package are the library's list.
TEST(Thumbnail, DataFilesListTheLibrarysMimeTypes) {
  const char* source = std::getenv("FACET_SOURCE_DIR");
  ASSERT_TRUE(source && *source) << "FACET_SOURCE_DIR must name the source tree (ctest sets it)";
  const std::string entry = read_text(fs::path(source) / "data" / "facet.thumbnailer");
  const std::size_t line = entry.find("\nMimeType=");
  ASSERT_NE(line, std::string::npos);
  std::vector<std::string> listed;
  std::istringstream types(entry.substr(line + 10, entry.find('\n', line + 1) - line - 10));
  for (std::string type; std::getline(types, type, ';');) listed.push_back(type);
  std::vector<std::string> expected;
  for (const ModelMimeType& type : thumbnail_mime_types()) expected.emplace_back(type.type);
  EXPECT_EQ(listed, expected);

  const std::string ours = read_text(fs::path(source) / "data" / "facet-mime.xml");
  const std::string debians = read_text("/usr/share/mime/packages/freedesktop.org.xml");
  ASSERT_FALSE(debians.empty()) << "Debian's shared-mime-info is installed by scripts/deps.sh";
  std::set<std::string> defined;
  for (const ModelMimeType& type : thumbnail_mime_types()) {
    SCOPED_TRACE(std::string(type.type));
    const std::string tag = "<mime-type type=\"" + std::string(type.type) + "\"";
    const std::string& database = type.facet_defines ? ours : debians;
    const std::size_t at = database.find(tag);
    ASSERT_NE(at, std::string::npos);
    const std::string definition = database.substr(at, database.find("</mime-type>", at) - at);
    EXPECT_NE(definition.find("<glob pattern=\"" + std::string(type.glob) + "\""), std::string::npos);
    EXPECT_EQ(debians.find(tag) == std::string::npos, type.facet_defines) << "defined in exactly one database";
    if (type.facet_defines) defined.emplace(type.type);
  }
  std::size_t ours_count = 0;
  for (std::size_t at = ours.find("<mime-type "); at != std::string::npos; at = ours.find("<mime-type ", at + 1))
    ++ours_count;
  EXPECT_EQ(ours_count, defined.size()) << "facet-mime.xml defines only listed types";
}

}  // namespace
}  // namespace facet::thumbnail_tests
