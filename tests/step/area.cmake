# Whole-step tests include the library's private headers (the state table, the simulation's
# state, zone validity) and set the OpenMP thread count.
target_include_directories(test_step PRIVATE ${PROJECT_SOURCE_DIR}/lib/src)
target_link_libraries(test_step PRIVATE OpenMP::OpenMP_CXX)
