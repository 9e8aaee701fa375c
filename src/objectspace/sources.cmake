# What several object-space techniques share (shadow-volume, dcs, penumbra-wedge, vtk), in double precision on the
# CPU and as GPU drawers: the casters' silhouettes and shadow volumes with their crossing counts and the counted
# point (receiver_offset), the potential-silhouette wedges (geometry, drawing, export), and the soft textured shadow
# volumes (STSV) of perforated casters. Above the passes, below the techniques.
set(SL_OBJECTSPACE_SOURCES
  src/objectspace/ShadowVolumeGeometry.cpp
  src/objectspace/ShadowVolumeReference.cpp
  src/objectspace/SilhouetteExport.cpp
  src/objectspace/DcsGeometry.cpp
  src/objectspace/DcsWedgeExport.cpp
  src/objectspace/WedgeDrawer.cpp
  src/objectspace/StsvGeometry.cpp
  src/objectspace/StsvDrawer.cpp)
