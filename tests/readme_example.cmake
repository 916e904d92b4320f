# Fails unless README.md quotes each of the examples verbatim, so the README's library examples
# are the code the build compiles and ctest runs.
file(READ "${SOURCE_DIR}/README.md" readme)
foreach(name trace_rays render_image)
  file(READ "${SOURCE_DIR}/examples/${name}.cpp" example)
  string(FIND "${readme}" "${example}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "README.md does not contain examples/${name}.cpp verbatim")
  endif()
endforeach()
