# The io tests include a driver header (the progress line's estimate, lib/src/driver/eta.hpp).
target_include_directories(test_io PRIVATE ${PROJECT_SOURCE_DIR}/lib/src)
