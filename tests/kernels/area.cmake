# Kernel tests include the library's private headers (header-only zone physics).
target_include_directories(test_kernels PRIVATE ${PROJECT_SOURCE_DIR}/lib/src)
target_link_libraries(test_kernels PRIVATE OpenMP::OpenMP_CXX)
