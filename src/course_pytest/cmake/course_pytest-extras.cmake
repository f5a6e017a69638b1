# course_add_pytests(DIR): the pytest tests under DIR (a package's test/unit) as a target of
# `catkin_make run_tests`, their JUnit XML in catkin's test results, where catkin_test_results
# counts them. Debian's catkin has catkin_add_nosetests but no pytest counterpart: this is the
# same wiring (catkin_run_tests_target) running `python3 -m pytest`.
# Call it inside if(CATKIN_ENABLE_TESTING), after find_package(course_pytest REQUIRED).
function(course_add_pytests dir)
  get_filename_component(_path "${dir}" ABSOLUTE BASE_DIR "${PROJECT_SOURCE_DIR}")
  if(NOT IS_DIRECTORY "${_path}")
    message(FATAL_ERROR "course_add_pytests(): no directory ${_path}")
  endif()
  file(RELATIVE_PATH _name "${PROJECT_SOURCE_DIR}" "${_path}")
  string(REPLACE "/" "." _name "${_name}")
  set(_results "${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}")
  set(_xml "pytest-${_name}.xml")
  # -B and no cache provider: a test run writes nothing into the source tree.
  catkin_run_tests_target("pytest" "${_name}" "${_xml}"
    COMMAND "\"${CMAKE_COMMAND}\" -E make_directory ${_results}"
            "${PYTHON_EXECUTABLE} -B -m pytest -q -p no:cacheprovider --junitxml=${_results}/${_xml} ${_path}")
endfunction()

# course_add_rostests(DIR): every DIR/*.test (a package's test/) as a rostest of
# `catkin_make run_tests`; a .test file added later is picked up at the next build.
# Call it inside if(CATKIN_ENABLE_TESTING), after find_package(course_pytest REQUIRED).
function(course_add_rostests dir)
  find_package(rostest REQUIRED)
  file(GLOB _tests RELATIVE "${PROJECT_SOURCE_DIR}" CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/${dir}/*.test")
  foreach(_test ${_tests})
    add_rostest(${_test})
  endforeach()
endfunction()
