# test_install installs this build tree and builds apps/examples/embed against it: it needs
# every installed target built, and the same toolchain for the example.
add_dependencies(test_install stagger stagger_meshgen stagger_scene stagger_cli)
target_compile_definitions(test_install PRIVATE
  STAGGER_CMAKE_COMMAND="${CMAKE_COMMAND}"
  STAGGER_CMAKE_GENERATOR="${CMAKE_GENERATOR}"
  STAGGER_MAKE_PROGRAM="${CMAKE_MAKE_PROGRAM}"
  STAGGER_CXX_COMPILER="${CMAKE_CXX_COMPILER}"
  STAGGER_INSTALL_LIBDIR="${CMAKE_INSTALL_LIBDIR}"
  STAGGER_SANITIZED=$<BOOL:${STAGGER_SANITIZE}>)
