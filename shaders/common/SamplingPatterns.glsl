// Sampling patterns of the filtering techniques (pcf, pcss, savsm), twins of src/techniques/SamplingPatterns:
// the fixed Poisson disk (MAX_POISSON_SAMPLES points in the unit disk, set by sl::setPoissonDiskUniform) and
// its per-pixel rotation.
uniform vec2 poissonDisk[MAX_POISSON_SAMPLES];

// Per-pixel pseudo-random rotation for sampling patterns (a 32-bit integer hash, "lowbias32" by Chris
// Wellons), exact in integer arithmetic so the CPU mirror (sl::pixelHash) reproduces it bit for bit.
uint pixelHash(uvec2 pixel)
{
  uint v = pixel.x * 1664525u + pixel.y * 1013904223u;
  v ^= v >> 16;
  v *= 0x7feb352du;
  v ^= v >> 15;
  v *= 0x846ca68bu;
  v ^= v >> 16;
  return v;
}

// Angle in [0, 2 pi).
float pixelHashAngle(uvec2 pixel)
{
  return float(pixelHash(pixel)) * (6.283185307179586 / 4294967296.0);
}

// The rotation by pixelHashAngle that decorrelates a pixel's Poisson taps from its neighbours'
// (rotation * p turns p counter-clockwise).
mat2 pixelRotation(uvec2 pixel)
{
  float angle = pixelHashAngle(pixel);
  return mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
}
