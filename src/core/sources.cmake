set(SL_CORE_SOURCES src/core/Error.cpp src/core/Parameters.cpp src/core/Progress.cpp)
