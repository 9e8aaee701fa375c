// The moment map's sparse blur (prefilter_region = receivers, sparse): vsm's and esm's moments of each tap, as
// MomentsFromDepth.glsl forms them, summed by the shared body.
#include "moments/MomentsOfDepth.glsl"
#include "moments/SparseBoxBlur.glsl"
