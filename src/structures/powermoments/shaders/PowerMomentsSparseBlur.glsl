// The power-moment map's sparse blur (prefilter_region = receivers, sparse): the power moments of each tap, as
// PowerMomentsFromDepth.glsl forms them, summed by the moment map's shared body.
#include "powermoments/PowerMomentsOfDepth.glsl"
#include "moments/SparseBoxBlur.glsl"
