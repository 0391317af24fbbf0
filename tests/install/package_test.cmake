# Installs the build into a fresh prefix and builds examples/decoder_hook.c against the
# installed package twice, once through CMake find_package (shared and static library)
# and once through pkg-config, then runs every build: all must add grain and print the
# same output. Run with: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DC_COMPILER=... -P
foreach(v BUILD_DIR SOURCE_DIR WORK_DIR C_COMPILER)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "${v} is not set")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The installed layout. The library directory is whatever GNUInstallDirs chose.
file(GLOB_RECURSE pc_files ${prefix}/*/filmgrain.pc)
list(LENGTH pc_files n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "expected one installed filmgrain.pc, found: ${pc_files}")
endif()
get_filename_component(pc_dir ${pc_files} DIRECTORY)
get_filename_component(libdir ${pc_dir} DIRECTORY)
foreach(f include/filmgrain/filmgrain.h include/filmgrain/filmgrain.hpp include/filmgrain/export.h
          include/filmgrain/frame.hpp include/filmgrain/error.hpp include/filmgrain/session.hpp bin/filmgrain)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
foreach(f libfilmgrain.so libfilmgrain.so.2 libfilmgrain.a cmake/filmgrain/filmgrainConfig.cmake
          cmake/filmgrain/filmgrainConfigVersion.cmake cmake/filmgrain/filmgrainTargets.cmake)
  if(NOT EXISTS ${libdir}/${f})
    message(FATAL_ERROR "not installed: ${libdir}/${f}")
  endif()
endforeach()

# 1. CMake find_package, both libraries.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK_DIR}/cmake-build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_C_COMPILER=${C_COMPILER} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/cmake-build)
run(${WORK_DIR}/cmake-build/decoder_hook)
set(out_cmake "${last_output}")
run(${WORK_DIR}/cmake-build/decoder_hook_static)
set(out_static "${last_output}")

# 2. pkg-config, as a Makefile would do it.
find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
run(${PKG_CONFIG} --cflags filmgrain)
string(STRIP "${last_output}" cflags)
run(${PKG_CONFIG} --libs filmgrain)
string(STRIP "${last_output}" libs)
separate_arguments(cflags UNIX_COMMAND "${cflags}")
separate_arguments(libs UNIX_COMMAND "${libs}")
run(${C_COMPILER} -std=c99 -Wall -Werror ${cflags} ${SOURCE_DIR}/examples/decoder_hook.c -o ${WORK_DIR}/decoder_hook_pc
    ${libs})
run(${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${libdir} ${WORK_DIR}/decoder_hook_pc)
set(out_pc "${last_output}")

message(STATUS "decoder_hook output:\n${out_cmake}")
if(NOT out_cmake MATCHES "frame 2: grain applied")
  message(FATAL_ERROR "unexpected output of the find_package build:\n${out_cmake}")
endif()
if(NOT out_cmake STREQUAL out_pc OR NOT out_cmake STREQUAL out_static)
  message(FATAL_ERROR "builds differ:\nfind_package:\n${out_cmake}\nstatic:\n${out_static}\npkg-config:\n${out_pc}")
endif()

# The installed library's symbols and dependencies: tests/install/library_boundary.cmake
# (its own test, package.library_boundary), here on the installed copy.
run(${CMAKE_COMMAND} -DLIBRARY=${libdir}/libfilmgrain.so -P ${SOURCE_DIR}/tests/install/library_boundary.cmake)

# The installed tool finds its image module (stills through OpenImageIO) where the install
# put it, relative to itself: a PGM in, a PNG out.
if(EXISTS ${BUILD_DIR}/filmgrain-oiio.so)
  if(NOT EXISTS ${libdir}/filmgrain/filmgrain-oiio.so)
    message(FATAL_ERROR "not installed: ${libdir}/filmgrain/filmgrain-oiio.so")
  endif()
  string(REPEAT "d" 128 pixels)
  file(WRITE ${WORK_DIR}/still.pgm "P5\n16 8\n255\n${pixels}")
  run(${prefix}/bin/filmgrain render ${WORK_DIR}/still.pgm -o ${WORK_DIR}/still.png --radius 0.3 --samples 8 -q)
  file(READ ${WORK_DIR}/still.png signature LIMIT 4 HEX)
  if(NOT signature STREQUAL "89504e47")
    message(FATAL_ERROR "the installed tool did not write a PNG (${signature})")
  endif()
endif()

# The Python module, when the build has it: Debian's python3 imports the installed package
# (PYTHONPATH = the directory the install put it in, not the build tree's) and applies grain
# to a tiny frame. Where the install puts it depends on the configured prefix (CMakeLists.txt:
# lib/python3/dist-packages for /usr, lib/python3.X/dist-packages for /usr/local,
# lib/python3.X/site-packages otherwise); the package is looked for under the prefix.
file(GLOB built_python_module ${BUILD_DIR}/python/filmgrain/_filmgrain*.so)
if(built_python_module)
  file(GLOB_RECURSE installed_init ${prefix}/lib/__init__.py)
  list(FILTER installed_init INCLUDE REGEX "/filmgrain/__init__.py$")
  list(LENGTH installed_init n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected one installed filmgrain/__init__.py under ${prefix}/lib, found: ${installed_init}")
  endif()
  get_filename_component(python_package ${installed_init} DIRECTORY)
  get_filename_component(python_dir ${python_package} DIRECTORY)
  file(GLOB installed_python_module ${python_package}/_filmgrain*.so)
  if(NOT installed_python_module)
    message(FATAL_ERROR "not installed: ${python_package}/_filmgrain*.so")
  endif()
  load_cache(${BUILD_DIR} READ_WITH_PREFIX cache_ Python_EXECUTABLE CMAKE_INSTALL_PREFIX)
  set(python ${cache_Python_EXECUTABLE})
  if(NOT python)
    set(python /usr/bin/python3)
  endif()
  # Installed into the configured prefix /usr or /usr/local, the same directory is on that
  # python3's own sys.path (no PYTHONPATH): Debian's searches /usr/lib/python3/dist-packages
  # and /usr/local/lib/python3.X/dist-packages, not /usr/local/lib/python3/dist-packages.
  file(RELATIVE_PATH python_dir_in_prefix ${prefix} ${python_dir})
  if(cache_CMAKE_INSTALL_PREFIX STREQUAL "/usr" OR cache_CMAKE_INSTALL_PREFIX STREQUAL "/usr/local")
    run(${python} -E -c "print(chr(10).join(__import__('sys').path))")
    string(REPLACE "\n" ";" python_sys_path "${last_output}")
    list(FIND python_sys_path "${cache_CMAKE_INSTALL_PREFIX}/${python_dir_in_prefix}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${cache_CMAKE_INSTALL_PREFIX}/${python_dir_in_prefix} (the module's place for the "
              "configured prefix) is not on ${python}'s sys.path:\n${last_output}")
    endif()
  endif()
  file(WRITE ${WORK_DIR}/installed_module.py [=[
import os, sys
import numpy as np
import filmgrain
where = os.path.realpath(filmgrain.__file__)
assert where.startswith(os.path.realpath(sys.argv[1]) + os.sep), "imported from " + where
print("filmgrain", filmgrain.__version__, "from", os.path.dirname(where))
s = filmgrain.Session(flavour="rdd5", threads=1)
s.push_fgc_sei(open(sys.argv[2], "rb").read(), "hevc", poc=0)
y = np.full((32, 48), 128, np.uint8)
c = np.full((16, 24), 128, np.uint8)
out = s.apply([y, c, c], poc=0)
assert s.last_result["grain_applied"], s.last_result["message"]
assert out[0].shape == y.shape and out[0].dtype == np.uint8 and not np.array_equal(out[0], y)
print("grain applied to a 48x32 frame")
]=])
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${python_dir} ${python} -s ${WORK_DIR}/installed_module.py ${python_dir}
      ${SOURCE_DIR}/conformance/rdd5_352x288_420p8/frame0.fgc.bin)
  message(STATUS "installed Python module:\n${last_output}")
endif()

# The GStreamer plugin, when the build has it: gst-inspect-1.0 finds the installed copy
# through GST_PLUGIN_PATH (a prefix other than /usr is not in GStreamer's own search path).
if(EXISTS ${BUILD_DIR}/gst-plugins/libgstfilmgrain.so)
  set(gst_dir ${libdir}/gstreamer-1.0)
  if(NOT EXISTS ${gst_dir}/libgstfilmgrain.so)
    message(FATAL_ERROR "not installed: ${gst_dir}/libgstfilmgrain.so")
  endif()
  find_program(GST_INSPECT gst-inspect-1.0 REQUIRED)
  run(${CMAKE_COMMAND} -E env GST_PLUGIN_PATH=${gst_dir} GST_REGISTRY_1_0=${WORK_DIR}/gst-registry.bin
      ${GST_INSPECT} filmgrain)
  if(NOT last_output MATCHES "Filename +${gst_dir}/libgstfilmgrain.so" OR NOT last_output MATCHES "filmgrainparse")
    message(FATAL_ERROR "gst-inspect-1.0 did not load the installed plugin ${gst_dir}/libgstfilmgrain.so:\n${last_output}")
  endif()
  message(STATUS "gst-inspect-1.0 filmgrain: the installed plugin, ${gst_dir}/libgstfilmgrain.so")
endif()
