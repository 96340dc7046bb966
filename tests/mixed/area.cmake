# Mixed-zone tests include the library's private headers (lib/src/mixed/).
target_include_directories(test_mixed PRIVATE ${PROJECT_SOURCE_DIR}/lib/src)
