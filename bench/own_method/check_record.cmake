# The run record of bar.json names the example's rotation method and smoother (cmake -P).
file(READ ${RECORD} record)
string(JSON rotation GET "${record}" analysis rotation)
string(JSON smoother GET "${record}" analysis multigrid smoother kind)
string(JSON converged GET "${record}" converged)
if(NOT rotation STREQUAL "energy-mueller-3" OR NOT smoother STREQUAL "damped-l1-jacobi"
   OR NOT converged)
  message(FATAL_ERROR "${RECORD}: rotation '${rotation}', smoother '${smoother}', "
                      "converged ${converged}")
endif()
