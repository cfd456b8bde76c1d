# The package test (ctest: package_test, label `package`): installs the build
# into a fresh temporary prefix, then configures, builds and runs the downstream
# project tests/package/ against that prefix alone. Any failing step fails the test.
# With -DPYTHON=<interpreter> and the Python module installed, the installed
# module is imported from the prefix alone and must run the installed program.
# cmake -DBUILD_DIR=<build> -DSOURCE_DIR=<tests/package> -DWORK_DIR=<scratch>
#       [-DGENERATOR=Ninja] [-DCXX_COMPILER=...] [-DCXX_FLAGS=...] [-DPYTHON=...] -P run_package_test.cmake
foreach(v BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT ${v})
    message(FATAL_ERROR "run_package_test.cmake: -D${v}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(app ${WORK_DIR}/app)

message(STATUS "cmake --install ${BUILD_DIR} --prefix ${prefix}")
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)

# Only the installed prefix: no package registry, no source or build tree of rheodda.
set(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${app} -DCMAKE_PREFIX_PATH=${prefix}
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(GENERATOR)
  list(APPEND configure -G ${GENERATOR})
endif()
if(CXX_COMPILER)
  list(APPEND configure -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(CXX_FLAGS)
  list(APPEND configure "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${CXX_FLAGS}")
endif()
execute_process(COMMAND ${configure} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${app} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${app}/rheodda_package_app ${SOURCE_DIR}/tiny-shear-creep.yaml COMMAND_ERROR_IS_FATAL ANY)

# The installed Python module (python/CMakeLists.txt) runs <prefix>/bin/rheodda, not the build's.
file(GLOB python_dirs ${prefix}/lib/python3*/*-packages)
if(PYTHON AND python_dirs)
  message(STATUS "the installed Python module from ${python_dirs}")
  set(check [=[
import os, subprocess, sys
import rheodda
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(rheodda.__file__).startswith(prefix + os.sep), rheodda.__file__
binary = rheodda.rheodda_binary()
assert os.path.samefile(binary, os.path.join(prefix, "bin", "rheodda")), binary
out = subprocess.run([binary, "--version"], capture_output=True, text=True, check=True).stdout
assert out.strip() == "rheodda " + rheodda.__version__, out
print("installed module", rheodda.__file__, "runs", binary)
]=])
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${python_dirs} ${PYTHON} -c "${check}" ${prefix}
    COMMAND_ERROR_IS_FATAL ANY)
endif()
file(REMOVE_RECURSE ${WORK_DIR})
