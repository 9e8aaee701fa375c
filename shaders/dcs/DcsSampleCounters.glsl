// Technique dcs: the per-pixel light-sample counters (src/techniques/dcs/vtkSLDcsPass.h). Layers 0 .. N/4 - 1 of an
// R32UI 2-D array hold four 8-bit counters each (sample i in layer i / 4, bits 8 (i % 4) ..), biased by
// DCS_COUNTER_BIAS: the change of sample i's depth complexity relative to the light's centre. Wedges add signed
// changes to whole words in any order; the sum modulo 2^32 is order-independent, so a word is right whenever every
// final counter lies in [0, 255] (the range check below). Three more layers follow: the two checksums of the range
// check, then the number of wedges that contain the pixel's point.
#define DCS_CHECKSUM_LAYER (lightSampleCount / 4)
#define DCS_WEIGHTED_CHECKSUM_LAYER (lightSampleCount / 4 + 1)
#define DCS_COVERING_LAYER (lightSampleCount / 4 + 2)
