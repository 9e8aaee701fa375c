// Technique dcs: one wedge's screen polygon (src/objectspace/DcsGeometry.h, "Where a wedge is drawn"), already in
// normalised device coordinates, fan-triangulated on the CPU; every vertex carries its wedge's index.
in vec2 wedgeNdcIn;
in float wedgeIndexIn; // exact: fewer than 2^24 wedges

flat out int wedgeIndex;

void main()
{
  wedgeIndex = int(wedgeIndexIn);
  gl_Position = vec4(wedgeNdcIn, 0.0, 1.0);
}
