# geo_sandbox_test checks that meshing leaves the OpenMP thread count alone.
target_link_libraries(test_mesh PRIVATE OpenMP::OpenMP_CXX)
# It also runs the real `stagger` binary (--threads 2 on a .geo scene).
add_dependencies(test_mesh stagger_cli)
