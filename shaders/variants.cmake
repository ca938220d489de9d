# Extra shader variants: lantern_compile_shader(<source> <variant> DEFINES NAME=VALUE ...).
# The default variant of every stage is compiled by shaders/CMakeLists.txt.
