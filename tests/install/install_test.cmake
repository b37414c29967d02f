# Installs the build tree into a temporary prefix, builds tests/install/consumer against it with
# find_package(lutex) and runs it (it restores a simulated image with a LUT it loads). Fails on any step.
# Run by CTest: cmake -D BUILD_DIR=... -D SOURCE_DIR=... -D WORK_DIR=... -D CXX_COMPILER=... -D CXX_FLAGS=...
# -P install_test.cmake. The consumer is built with the tree's compiler and flags, as a project that embeds
# the static libraries must be (a sanitized tree's libraries need the sanitizer's runtime).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed (${result}): ${ARGN}\n${err}")
  endif()
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
foreach(path bin/lutex include/lutex/lib/restoration/restorer.h lib/cmake/lutex/lutexConfig.cmake)
  if(NOT EXISTS ${WORK_DIR}/prefix/${path})
    message(FATAL_ERROR "the install lacks ${path}")
  endif()
endforeach()
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${WORK_DIR}/build -G Ninja
     -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
     "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${WORK_DIR}/build/restore_one_image ${WORK_DIR}/true.lut)
file(REMOVE_RECURSE ${WORK_DIR})
