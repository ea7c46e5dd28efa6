# The GPU sweep's device code (gpu/runtime.cu) needs nvcc; everything else builds and runs
# without it. DAMPBOUND_CUDA (on by default) compiles it where nvcc is found, on PATH, in
# $CUDACXX or at /usr/local/cuda/bin/nvcc, and can compile a CUDA program with this host
# compiler; DAMPBOUND_HAS_CUDA says whether it does, and configure prints why not.
option(DAMPBOUND_CUDA "Compile the GPU sweep's device code with nvcc where it is found" ON)
set(DAMPBOUND_CUDA_ARCHITECTURES "80-virtual;90-real" CACHE STRING
    "CUDA targets of the GPU sweep: machine code for compute capability 9.0 (H100, H200) and PTX that the driver compiles for 8.0 and newer")
set(DAMPBOUND_HAS_CUDA OFF)
if(DAMPBOUND_CUDA)
  if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX} AND EXISTS /usr/local/cuda/bin/nvcc)
    set(ENV{CUDACXX} /usr/local/cuda/bin/nvcc)
  endif()
  include(CheckLanguage)
  check_language(CUDA)  # compiles a test program: an nvcc that cannot (host compiler too new) gives NOTFOUND
  if(CMAKE_CUDA_COMPILER)
    set(CMAKE_CUDA_ARCHITECTURES ${DAMPBOUND_CUDA_ARCHITECTURES})
    enable_language(CUDA)
    find_package(CUDAToolkit REQUIRED)
    set(DAMPBOUND_HAS_CUDA ON)
    message(STATUS "GPU sweep: device code compiled by ${CMAKE_CUDA_COMPILER} "
                   "(CUDA ${CMAKE_CUDA_COMPILER_VERSION}, ${DAMPBOUND_CUDA_ARCHITECTURES})")
  elseif(DEFINED ENV{CUDACXX} OR EXISTS /usr/local/cuda/bin/nvcc)
    message(STATUS "GPU sweep: off: nvcc is there but cannot compile a CUDA program with this "
                   "host compiler (${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}); "
                   "see CMakeFiles/CMakeError.log. `sweep --device gpu` will say so")
  else()
    message(STATUS "GPU sweep: off: no nvcc (CUDA toolkit) found; `sweep --device gpu` will say so")
  endif()
else()
  message(STATUS "GPU sweep: off (DAMPBOUND_CUDA=OFF)")
endif()
