# The scene module: scene.json parsing and validation, primitives, mesh and alpha-texture loading.
set(SL_SCENE_SOURCES
  src/scene/Scene.cpp
  src/scene/SceneLoader.cpp
  src/scene/Primitives.cpp
  src/scene/MeshIO.cpp
  src/scene/AlphaTexture.cpp
  src/scene/RayTriangle.cpp
  src/scene/WeldedMesh.cpp
  src/scene/AlphaMesh.cpp
  src/scene/RandomScenes.cpp)
# GCC 12 reports a false -Wmaybe-uninitialized inside libstdc++'s allocator while instantiating OpenMesh's
# property containers; the warning is about library code, not ours.
set_source_files_properties(src/scene/MeshIO.cpp PROPERTIES COMPILE_OPTIONS -Wno-maybe-uninitialized)
