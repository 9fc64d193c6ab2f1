# TestInstallTree: install the build tree into a fresh prefix and use it from outside.
#
#   cmake -DBUILD_DIR=<cbc3d build> -DSOURCE_DIR=<cbc3d source> -DWORK_DIR=<scratch folder>
#         [-DGENERATOR=<generator>] [-DCXX_COMPILER=<c++>] [-DC_COMPILER=<cc>]
#         [-DPVPYTHON=<pvpython>] -P TestInstallTree.cmake
#
# 1. `cmake --install BUILD_DIR --prefix WORK_DIR/prefix`;
# 2. the prefix holds the library, the public headers, the package files, the command and the
#    plugin, and nothing of the private VTK-free core (no vtkCBC3DConvert.h, no cbc3d/ headers,
#    no static core library (libcbc3d_*.a); the exported target names no core stage, Eigen nor OpenMP);
# 3. the installed command and plugin find the installed libvtkCBC3DFilters.so through their
#    RPATHs (ldd), and the installed command meshes Data/ball.vti;
# 4. the outside project Testing/Install/Consumer is configured with only
#    CMAKE_PREFIX_PATH=<prefix>, once finding CBC3D alone and once after find_package(ParaView),
#    built, and run (it meshes a ball in memory and checks the angles and labels);
# 5. with PVPYTHON, the installed plugin loads and runs, with the installed library.
# Everything is written under WORK_DIR (in the build tree). Fails with FATAL_ERROR (exit 1).
cmake_minimum_required(VERSION 3.16)

foreach(var BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "${var} is required")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

string(TIMESTAMP start "%s")
macro(step title)
  string(TIMESTAMP now "%s")
  math(EXPR elapsed "${now} - ${start}")
  message(STATUS "[${elapsed} s] ${title}")
endmacro()

function(run_checked)
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE result
    OUTPUT_VARIABLE output
    ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${command}\n${output}")
  endif()
  set(run_output "${output}" PARENT_SCOPE)
endfunction()

# 1. Install.
step("install ${BUILD_DIR} into ${prefix}")
run_checked("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")

# 2. What is there and what is not.
step("check the installed files")
set(expected
  bin/cbc3d
  libexec/cbc3d/cbc3d
  lib/libvtkCBC3DFilters.so
  lib/libcbc3dBinaryFormats.so
  lib/paraview-5.11/plugins/CBC3D/CBC3D.so
  include/cbc3d/vtkCBC3DFiltersModule.h
  include/cbc3d/vtkCBC3DAlgorithm.h
  include/cbc3d/vtkCBC3DArrayNames.h
  include/cbc3d/vtkCBC3DBCCLattice.h
  include/cbc3d/vtkCBC3DMeshQuality.h
  include/cbc3d/vtkCBC3DNIfTIReader.h
  lib/cmake/cbc3d/CBC3DConfig.cmake
  lib/cmake/cbc3d/CBC3DConfigVersion.cmake
  lib/cmake/cbc3d/CBC3D-targets.cmake
  lib/cmake/cbc3d/CBC3D-vtk-module-properties.cmake
  lib/cmake/cbc3d/CBC3D-vtk-module-find-packages.cmake)
foreach(file IN LISTS expected)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()
file(GLOB_RECURSE installed RELATIVE "${prefix}" "${prefix}/*")
foreach(file IN LISTS installed)
  if(file MATCHES "vtkCBC3DConvert|libcbc3d_[a-z]+\\.a|/cbc3d/cbc3d/|include/cbc3d/([a-z]+/)?[A-Z][A-Za-z]*\\.h$"
      AND NOT file MATCHES "include/cbc3d/vtk")
    message(FATAL_ERROR "private file installed: ${file}")
  endif()
endforeach()
file(GLOB headers "${prefix}/include/cbc3d/*.h")
foreach(header IN LISTS headers)
  file(STRINGS "${header}" includes REGEX "^[ \t]*#[ \t]*include")
  foreach(line IN LISTS includes)
    if(line MATCHES "cbc3d/|Eigen|omp\\.h|vtkCBC3DConvert")
      message(FATAL_ERROR "${header} includes a private header: ${line}")
    endif()
  endforeach()
endforeach()
file(GLOB exports "${prefix}/lib/cmake/cbc3d/CBC3D-targets*.cmake")
foreach(export IN LISTS exports)
  file(READ "${export}" content)
  if(content MATCHES "cbc3d_(core|base|sampling|lattice|soundlabels|refinement|quality|export|deformation)[^a-z]|Eigen|OpenMP")
    message(FATAL_ERROR "${export} names a private dependency (${CMAKE_MATCH_0})")
  endif()
endforeach()

# 3. RPATHs: the installed binaries find the installed library, and the command works.
find_program(LDD ldd)
if(LDD)
  step("ldd on the installed command, its mesher and the plugin")
  run_checked("${LDD}" "${prefix}/bin/cbc3d")
  if(run_output MATCHES "libvtk")
    message(FATAL_ERROR "the launcher bin/cbc3d loads VTK\n${run_output}")
  endif()
  foreach(binary libexec/cbc3d/cbc3d lib/paraview-5.11/plugins/CBC3D/CBC3D.so)
    run_checked("${LDD}" "${prefix}/${binary}")
    if(run_output MATCHES "not found")
      message(FATAL_ERROR "${binary}: unresolved libraries\n${run_output}")
    endif()
    if(NOT run_output MATCHES "libvtkCBC3DFilters\\.so => ([^ ]+)")
      message(FATAL_ERROR "${binary} does not load libvtkCBC3DFilters.so\n${run_output}")
    endif()
    get_filename_component(resolved "${CMAKE_MATCH_1}" REALPATH)
    if(NOT resolved STREQUAL "${prefix}/lib/libvtkCBC3DFilters.so")
      message(FATAL_ERROR "${binary} loads ${resolved}, not the installed library")
    endif()
    # netCDF and HDF5 come only with the writers that need them, loaded when used.
    if(run_output MATCHES "libnetcdf|libhdf5")
      message(FATAL_ERROR "${binary} loads netCDF or HDF5 at start\n${run_output}")
    endif()
  endforeach()
  run_checked("${LDD}" "${prefix}/lib/libcbc3dBinaryFormats.so")
  if(run_output MATCHES "not found")
    message(FATAL_ERROR "libcbc3dBinaryFormats.so: unresolved libraries\n${run_output}")
  endif()
endif()
step("the installed cbc3d meshes Data/ball.vti")
run_checked("${prefix}/bin/cbc3d" "${SOURCE_DIR}/Data/ball.vti" -o "${WORK_DIR}/ball.vtu"
  --bcc-size 2 --quiet)
if(NOT EXISTS "${WORK_DIR}/ball.vtu")
  message(FATAL_ERROR "the installed cbc3d wrote no ball.vtu")
endif()
step("the installed cbc3d writes Exodus II and XDMF (the writers it loads when used)")
run_checked("${prefix}/bin/cbc3d" "${SOURCE_DIR}/Data/ball.vti" -o "${WORK_DIR}/ball.exo"
  --bcc-size 2 --quiet)
run_checked("${prefix}/bin/cbc3d" "${SOURCE_DIR}/Data/ball.vti" -o "${WORK_DIR}/ball.xdmf"
  --bcc-size 2 --quiet)
foreach(file ball.exo ball.xdmf ball.h5)
  if(NOT EXISTS "${WORK_DIR}/${file}")
    message(FATAL_ERROR "the installed cbc3d wrote no ${file}")
  endif()
endforeach()

# 4. The outside project, twice.
set(generator_args)
if(GENERATOR)
  list(APPEND generator_args -G "${GENERATOR}")
endif()
if(CXX_COMPILER)
  list(APPEND generator_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
if(C_COMPILER)
  list(APPEND generator_args "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif()
foreach(paraview_first OFF ON)
  set(consumer_build "${WORK_DIR}/consumer-paraview-first-${paraview_first}")
  step("configure the consumer (find_package(ParaView) first: ${paraview_first})")
  run_checked("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Testing/Install/Consumer"
    -B "${consumer_build}" ${generator_args}
    -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${prefix}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCONSUMER_FIND_PARAVIEW_FIRST=${paraview_first})
  file(STRINGS "${consumer_build}/CMakeCache.txt" cbc3d_dir REGEX "^CBC3D_DIR:")
  if(NOT cbc3d_dir STREQUAL "CBC3D_DIR:PATH=${prefix}/lib/cmake/cbc3d")
    message(FATAL_ERROR "the consumer found another CBC3D: ${cbc3d_dir}")
  endif()
  string(FIND "${run_output}" "CBC3D plugin: ${prefix}/lib/paraview-5.11/plugins/CBC3D/CBC3D.so" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "CBC3D_PLUGIN is not the installed plugin:\n${run_output}")
  endif()
  step("build the consumer")
  run_checked("${CMAKE_COMMAND}" --build "${consumer_build}")
  if(LDD)
    run_checked("${LDD}" "${consumer_build}/cbc3d_consumer")
    if(NOT run_output MATCHES "libvtkCBC3DFilters\\.so => ${prefix}/lib/libvtkCBC3DFilters\\.so")
      message(FATAL_ERROR "the consumer does not load the installed library\n${run_output}")
    endif()
  endif()
  step("run the consumer")
  run_checked("${consumer_build}/cbc3d_consumer")
  message(STATUS "${run_output}")
endforeach()

# 5. The installed plugin in pvpython.
if(PVPYTHON)
  step("load the installed plugin in pvpython")
  file(WRITE "${WORK_DIR}/load_installed_plugin.py" "
import sys
from paraview.simple import *
plugin = '${prefix}/lib/paraview-5.11/plugins/CBC3D/CBC3D.so'
LoadPlugin(plugin, remote=False, ns=globals())
image = OpenDataFile('${SOURCE_DIR}/Data/ball.vti')
lattice = CBC3DBCCLattice(Input=image, EdgeLength=2.0)
quality = CBC3DMeshQuality(Input=lattice, Image=image)
quality.UpdatePipeline()
cells = quality.GetDataInformation().GetNumberOfCells()
libraries = [line.split()[-1] for line in open('/proc/self/maps') if 'libvtkCBC3DFilters' in line]
print('cells', cells, 'libraries', sorted(set(libraries)))
ok = cells > 0 and set(libraries) == {'${prefix}/lib/libvtkCBC3DFilters.so'}
sys.exit(0 if ok else 1)
")
  run_checked("${PVPYTHON}" "${WORK_DIR}/load_installed_plugin.py")
  message(STATUS "${run_output}")
endif()

step("done")
