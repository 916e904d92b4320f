# Writes <build>/referenced-files.txt: every absolute path that our dependencies' imported
# targets name (library and tool locations, include directories, link items), one
# "imported target NAME<TAB>PATH" line each. tools/check-deps.sh maps them to Debian packages:
# a target's file that comes from a package install-deps.sh does not install is exactly the
# kind of mistake that broke the quick start (OpenImageIO::iconvert -> openimageio-tools).

function(_wavetrace_imported_targets dir out)
  get_directory_property(targets DIRECTORY ${dir} IMPORTED_TARGETS)
  get_directory_property(subdirs DIRECTORY ${dir} SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _wavetrace_imported_targets(${sub} sub_targets)
    list(APPEND targets ${sub_targets})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

function(wavetrace_write_referenced_files file)
  _wavetrace_imported_targets(${PROJECT_SOURCE_DIR} targets)
  list(REMOVE_DUPLICATES targets)
  set(lines "")
  foreach(target IN LISTS targets)
    set(properties IMPORTED_LOCATION IMPORTED_IMPLIB INTERFACE_INCLUDE_DIRECTORIES
                   INTERFACE_SYSTEM_INCLUDE_DIRECTORIES INTERFACE_LINK_LIBRARIES)
    get_target_property(configs ${target} IMPORTED_CONFIGURATIONS)
    if(configs)
      foreach(config IN LISTS configs)
        list(APPEND properties IMPORTED_LOCATION_${config} IMPORTED_IMPLIB_${config})
      endforeach()
    endif()
    foreach(property IN LISTS properties)
      get_target_property(values ${target} ${property})
      if(NOT values)
        continue()
      endif()
      foreach(value IN LISTS values)
        # Link items may be wrapped in generator expressions such as $<LINK_ONLY:...>.
        string(REGEX REPLACE "^\\$<[A-Z_]+:(.*)>$" "\\1" value "${value}")
        if(value MATCHES "^/")
          string(APPEND lines "imported target ${target}\t${value}\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
  file(WRITE ${file} "${lines}")
endfunction()
