# The run record of bar.json names the example's rotation method and smoother, and the smoother
# ran with the scene's own value of its own setting, jacobi_damping 0.7 (its default is 0.8)
# (cmake -P).
file(READ ${RECORD} record)
string(JSON rotation GET "${record}" analysis rotation)
string(JSON smoother GET "${record}" analysis multigrid smoother kind)
string(JSON damping GET "${record}" analysis multigrid smoother damping)
string(JSON converged GET "${record}" converged)
if(NOT rotation STREQUAL "energy-mueller-3" OR NOT smoother STREQUAL "damped-l1-jacobi"
   OR NOT damping EQUAL 0.7 OR NOT converged)
  message(FATAL_ERROR "${RECORD}: rotation '${rotation}', smoother '${smoother}', damping "
                      "${damping}, converged ${converged}")
endif()
