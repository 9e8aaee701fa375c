# The scene module: scene.json parsing and validation, primitives, mesh and alpha-texture loading.
set(SL_SCENE_SOURCES
  src/scene/Scene.cpp
  src/scene/SceneLoader.cpp
  src/scene/Primitives.cpp
  src/scene/MeshIO.cpp
  src/scene/AlphaTexture.cpp)
