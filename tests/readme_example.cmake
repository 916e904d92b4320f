# Fails unless README.md quotes examples/trace_rays.cpp verbatim, so the README's library
# example is the code the build compiles and ctest runs.
file(READ "${SOURCE_DIR}/README.md" readme)
file(READ "${SOURCE_DIR}/examples/trace_rays.cpp" example)
string(FIND "${readme}" "${example}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "README.md does not contain examples/trace_rays.cpp verbatim")
endif()
