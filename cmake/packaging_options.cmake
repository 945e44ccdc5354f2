# packaging_options.cmake - read by cpack (CPACK_PROJECT_CONFIG_FILE) each time it runs a generator.
# Without a summary, CPackDeb takes the first line of each package's own description as its synopsis, instead of
# putting the project's one summary before both packages' descriptions.
unset(CPACK_PACKAGE_DESCRIPTION_SUMMARY)
