# course_add_tests(): every test a package has, as targets of `catkin_make run_tests`, found
# by where the package keeps them (the house layout):
#   launch/       roslaunch's check of every launch file (roslaunch_add_file_check)
#   test/*.test   a rostest each (course_add_rostests)
#   test/unit/    pytest (course_add_pytests)
# What a package lacks is skipped; whether launch/ and test/unit/ exist is read when CMake
# configures, a .test file added later is found at the next build. A package that has launch
# files or .test files declares <test_depend>roslaunch</test_depend> or
# <test_depend>rostest</test_depend> in its package.xml: the find_package() calls are in here,
# where catkin_lint does not see them, so this function checks those two itself.
# A package's testing block, after catkin_package():
#   if(CATKIN_ENABLE_TESTING)
#     find_package(course_pytest REQUIRED)
#     course_add_tests()
#   endif()
function(course_add_tests)
  if(ARGN)
    message(FATAL_ERROR "course_add_tests() takes no arguments (given: ${ARGN}): it registers "
      "launch/, test/*.test and test/unit/ where the package has them")
  endif()
  if(NOT _CATKIN_CURRENT_PACKAGE STREQUAL PROJECT_NAME)
    message(FATAL_ERROR "course_add_tests(): call it after catkin_package() (it reads the "
      "package.xml that catkin_package() parses)")
  endif()
  if(IS_DIRECTORY "${PROJECT_SOURCE_DIR}/launch")
    _course_require_test_depend(roslaunch "its launch/ is checked by roslaunch")
    find_package(roslaunch REQUIRED)
    roslaunch_add_file_check(launch)
  endif()
  file(GLOB _tests CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/test/*.test")
  if(_tests)
    _course_require_test_depend(rostest "its test/*.test are run by rostest")
    course_add_rostests(test)
  endif()
  if(IS_DIRECTORY "${PROJECT_SOURCE_DIR}/test/unit")
    course_add_pytests(test/unit)
  endif()
endfunction()

# course_add_tests()'s check that package.xml declares what runs a kind of test (a test or a
# build dependency, as catkin_lint accepts for a find_package() in the testing block).
function(_course_require_test_depend dep why)
  list(FIND ${PROJECT_NAME}_TEST_DEPENDS ${dep} _test)
  list(FIND ${PROJECT_NAME}_BUILD_DEPENDS ${dep} _build)
  if(_test EQUAL -1 AND _build EQUAL -1)
    message(FATAL_ERROR "${PROJECT_NAME}: ${why}: add <test_depend>${dep}</test_depend> to "
      "${PROJECT_SOURCE_DIR}/package.xml")
  endif()
endfunction()

# course_add_pytests(DIR): the pytest tests under DIR (a package's test/unit) as a target of
# `catkin_make run_tests`, their JUnit XML in catkin's test results, where catkin_test_results
# counts them. Debian's catkin has catkin_add_nosetests but no pytest counterpart: this is the
# same wiring (catkin_run_tests_target) running `python3 -m pytest`. course_add_tests() calls it
# for test/unit; call it yourself only for tests kept elsewhere, inside if(CATKIN_ENABLE_TESTING),
# after find_package(course_pytest REQUIRED).
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
# course_add_tests() calls it for test/; call it yourself only for .test files kept elsewhere,
# inside if(CATKIN_ENABLE_TESTING), after find_package(course_pytest REQUIRED).
function(course_add_rostests dir)
  find_package(rostest REQUIRED)
  file(GLOB _tests RELATIVE "${PROJECT_SOURCE_DIR}" CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/${dir}/*.test")
  foreach(_test ${_tests})
    add_rostest(${_test})
  endforeach()
endfunction()
