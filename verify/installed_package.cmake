# InstalledPackage.OwnMethodExample (cmake -P): corofem installed into a fresh prefix,
# bench/own_method configured with find_package(corofem CONFIG) against it, built, and its own
# tests run. Any step that fails fails the gate, with that step's output.
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
if(NOT EXISTS ${WORK_DIR}/prefix/lib/cmake/corofem/corofemConfig.cmake
   AND NOT EXISTS ${WORK_DIR}/prefix/lib64/cmake/corofem/corofemConfig.cmake)
  file(GLOB_RECURSE configs ${WORK_DIR}/prefix/*Config.cmake)
  if(NOT configs)
    message(FATAL_ERROR "the install has no corofemConfig.cmake")
  endif()
endif()
step("configure bench/own_method" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/bench/own_method
     -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
step("build bench/own_method" ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j 2)
step("bench/own_method's tests" ${CTEST} --test-dir ${WORK_DIR}/build --output-on-failure)
