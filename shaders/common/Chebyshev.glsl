// The variance bound of vsm and savsm (Donnelly & Lauritzen 2006; Eq. 1, VSSM): for depths with `mean` and
// `variance` over a filter region, the fraction at or beyond the receiver depth t is at most
//   p_max = variance / (variance + (t - mean)^2)   for t > mean (1 otherwise),
// and light bleeding is reduced by mapping [amount, 1] to [0, 1] (Lauritzen 2007).
float chebyshevUpperBound(float mean, float variance, float t)
{
  return t <= mean ? 1.0 : variance / (variance + (t - mean) * (t - mean));
}

float reduceLightBleeding(float pMax, float amount)
{
  return clamp((pMax - amount) / (1.0 - amount), 0.0, 1.0);
}
