# InstalledPackage.OwnMethodExample (cmake -P): corofem installed into a fresh prefix,
# bench/own_method configured with find_package(corofem CONFIG) against it, built, and its own
# tests run (at least one). Any step that fails fails the gate, with that step's output.
foreach(var BINARY_DIR SOURCE_DIR WORK_DIR BUILD_TYPE CTEST)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "installed_package.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})

function(step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${name} failed (${status}):\n${out}\n${err}")
  endif()
  message(STATUS "${name}: done")
endfunction()

step("cmake --install" ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK_DIR}/prefix)
# The package's own config file, where GNUInstallDirs puts it on Debian (lib/) or elsewhere
# (lib64/): another package's *Config.cmake is no corofem package.
file(GLOB configs ${WORK_DIR}/prefix/lib/cmake/corofem/corofemConfig.cmake
     ${WORK_DIR}/prefix/lib64/cmake/corofem/corofemConfig.cmake)
if(NOT configs)
  message(FATAL_ERROR "the install has no lib/cmake/corofem/corofemConfig.cmake")
endif()
step("configure bench/own_method" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/bench/own_method
     -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
step("build bench/own_method" ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j 2)
# --no-tests=error: an example whose tests vanished (a CMakeLists without enable_testing, a
# discovery that found none) fails here instead of passing with nothing run.
step("bench/own_method's tests" ${CTEST} --test-dir ${WORK_DIR}/build --output-on-failure
     --no-tests=error)
