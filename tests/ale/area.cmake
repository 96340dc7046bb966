# ALE tests include the library's private headers (rezone, remap) and Eigen for references.
target_include_directories(test_ale PRIVATE ${PROJECT_SOURCE_DIR}/lib/src)
target_link_libraries(test_ale PRIVATE OpenMP::OpenMP_CXX Eigen3::Eigen)
