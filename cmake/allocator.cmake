# The memory allocator of the `lutex` executable and of the benchmarks (which run its stages in-process):
# gperftools' tcmalloc (tcmalloc_minimal, Debian's libgoogle-perftools-dev) by default, glibc's malloc with
# -DLUTEX_MALLOC=system. The libraries (lutex::lutex) never choose one for the program that links them.
#
# Why: the tiled bake allocates and frees buffers of megabytes tile after tile (texels, decoded images,
# ray-cast maps). glibc serves them from its heaps once a freed mapping has raised its mmap threshold, and
# keeps the freed space between live blocks; below the threshold it maps and zeroes fresh pages every time.
# tcmalloc keeps freed spans for reuse and returns them to the system a little at a time. Measured with the
# same binary (README, "Speed and memory" under `lutex tiles`): `lutex tiles` on the 12 MP workspace 77 s
# instead of 86 s (system time 4 s instead of 14 s) for 2.5 % more peak memory, and on the 5 M-face dive a
# peak of 360 MiB instead of 423 in 123 s instead of 127; jemalloc and mimalloc returned memory sooner and
# took 40-45 % longer at 12 MP. The output does not depend on the allocator (the tiles compared byte for
# byte).
#
# The sanitizer and fuzzing builds bring their own allocator (AddressSanitizer's): there no other is linked.
set(LUTEX_MALLOC "tcmalloc" CACHE STRING
  "Allocator of the lutex executable and the benchmarks: tcmalloc (gperftools) or system (glibc)")
set_property(CACHE LUTEX_MALLOC PROPERTY STRINGS tcmalloc system)

add_library(lutex_malloc INTERFACE)
if(NOT LUTEX_MALLOC MATCHES "^(tcmalloc|system)$")
  message(FATAL_ERROR "LUTEX_MALLOC is '${LUTEX_MALLOC}'; it must be tcmalloc or system")
endif()
if(LUTEX_FUZZERS OR CMAKE_CXX_FLAGS MATCHES "-fsanitize=")
  if(LUTEX_MALLOC STREQUAL "tcmalloc")
    message(STATUS "lutex: the sanitizers bring their own allocator; tcmalloc is not linked")
  endif()
elseif(LUTEX_MALLOC STREQUAL "tcmalloc")
  find_library(LUTEX_TCMALLOC_LIBRARY tcmalloc_minimal)
  if(NOT LUTEX_TCMALLOC_LIBRARY)
    message(FATAL_ERROR "lutex: tcmalloc (libtcmalloc_minimal) not found: install Debian's libgoogle-perftools-dev "
                        "(scripts/install_dependencies.sh does), or configure with -DLUTEX_MALLOC=system for glibc's malloc")
  endif()
  target_link_libraries(lutex_malloc INTERFACE ${LUTEX_TCMALLOC_LIBRARY})
endif()
