// Technique dcs: the per-pixel light-sample counters (src/techniques/dcs/vtkSLDcsPass.h; the layout is
// DcsTechnique.h's DcsCounterLayers, whose layer indices and packing the preamble defines). Layers
// 0 .. DCS_SAMPLE_COUNTER_LAYERS - 1 of an R32UI 2-D array hold DCS_COUNTERS_PER_LAYER counters of DCS_COUNTER_BITS
// each (sample i in layer i / DCS_COUNTERS_PER_LAYER), biased by DCS_COUNTER_BIAS: the change of sample i's depth
// complexity relative to the light's centre. Wedges add signed changes to whole words in any order; the sum modulo
// 2^32 is order-independent, so a word is right whenever every final counter lies in [0, DCS_COUNTER_MASK] (the
// range check). The layers DCS_CHECKSUM_LAYER and DCS_WEIGHTED_CHECKSUM_LAYER hold the two checksums of the range
// check, DCS_COVERING_LAYER the number of wedges that contain the pixel's point.

// The layer of sample `index`'s counter, and the shift of its bits in that layer's word.
int dcsCounterLayer(int index)
{
  return index / DCS_COUNTERS_PER_LAYER;
}

uint dcsCounterShift(int index)
{
  return uint(DCS_COUNTER_BITS * (index % DCS_COUNTERS_PER_LAYER));
}
