# The catalogue runs the real `stagger` binary (bin/stagger): build it first.
add_dependencies(test_bad_inputs stagger_cli)
