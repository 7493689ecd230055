# The floating-point model of the reference and the framework.
#
# The watertight triangle test relies on an edge shared by two triangles giving exactly
# opposite edge functions, x1 * y2 - y1 * x2 and x2 * y1 - y2 * x1. A compiler that fuses
# one product into an FMA (clang's default -ffp-contract=on, GCC's =fast with
# -march=native) rounds the two differently and rays leak through shared edges. So:
# no contraction, and never -ffast-math (it also drops the NaN and infinity semantics
# the slab test and the validation rely on).
add_compile_options(-ffp-contract=off)
foreach(flags CMAKE_CXX_FLAGS CMAKE_CXX_FLAGS_RELEASE CMAKE_CXX_FLAGS_RELWITHDEBINFO)
  if("${${flags}}" MATCHES "fast-math|-Ofast")
    message(FATAL_ERROR "${flags} holds -ffast-math or -Ofast: raylab's numerics need "
                        "IEEE semantics (cmake/FloatingPoint.cmake)")
  endif()
endforeach()
