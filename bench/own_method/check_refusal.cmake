# bar.json with analysis.jacobi_damping 2, outside the (0.05, 1] the smoother declares: own_method
# exits 2 naming the key, and writes nothing (cmake -P).
file(READ ${SCENE} scene)
string(JSON scene SET "${scene}" analysis jacobi_damping 2)
file(WRITE ${WORK}/bar-damping-2.json "${scene}")
execute_process(COMMAND ${OWN_METHOD} run ${WORK}/bar-damping-2.json --out ${WORK}/refused.json
                RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT status EQUAL 2 OR NOT err MATCHES "analysis.jacobi_damping must be in \\[0.05, 1\\]"
   OR EXISTS ${WORK}/refused.json)
  message(FATAL_ERROR "status ${status}: ${err}")
endif()
