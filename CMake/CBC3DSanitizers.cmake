# Options for the sanitizer job (scripts/sanitizer-job.sh) and the libFuzzer fuzzers.
#
# CBC3D_SANITIZE: every target of this project is built with AddressSanitizer (LeakSanitizer
# included, ASan's default on Linux) and UndefinedBehaviorSanitizer, and any UB report aborts
# (-fno-sanitize-recover), so a test that triggers one fails. Debian's VTK, Python, OpenMP and
# HDF5 stay uninstrumented; Testing/Fuzz/sanitizer-suppressions.txt names their reports.
#
# CBC3D_FUZZERS: builds the libFuzzer targets of Testing/Fuzz (clang only). The project's own
# code is compiled with coverage instrumentation (-fsanitize=fuzzer-no-link) so that libFuzzer
# sees which branches an input reaches; only the fuzzer executables link libFuzzer's main.
option(CBC3D_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(CBC3D_FUZZERS "Build the libFuzzer fuzzers (clang; implies nothing else)" OFF)

if(CBC3D_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang|GNU")
    message(FATAL_ERROR "CBC3D_SANITIZE needs clang or gcc")
  endif()
  set(cbc3d_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all)
  # _GLIBCXX_ASSERTIONS: bounds checks on std::vector and friends, which ASan misses inside
  # a vector's capacity.
  add_compile_options(${cbc3d_sanitizers} -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS)
  add_link_options(${cbc3d_sanitizers})
endif()

if(CBC3D_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "CBC3D_FUZZERS needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
