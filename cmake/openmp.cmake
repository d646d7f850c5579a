# OpenMP (Debian: part of g++; libomp-dev for clang). Provides OpenMP::OpenMP_CXX.
find_package(OpenMP REQUIRED COMPONENTS CXX)
