// The foam paper's scalar functions (Akinci et al. 2013, "Screen space foam rendering"), shared by the foam
// passes and checked against their formulas by tests/native/test_foam_functions.cpp.

// Equation 1, the falloff f(x, b, n, m) = (1 - (x / b)^n)^m for 0 <= x / b <= 1, else 0. Exponents of 0 are
// the limits (x/b)^0 = 1 and y^0 = 1, which GLSL's pow leaves undefined at 0.
float foamFalloff(float x, float b, float n, float m) {
  float ratio = x / b;
  if (!(ratio >= 0.0 && ratio <= 1.0)) return 0.0;
  float inner = 1.0 - (n == 0.0 ? 1.0 : pow(ratio, n));
  return m == 0.0 ? 1.0 : pow(max(inner, 0.0), m);
}

// Section 2.3, the sigmoid iota(rho, rho_mod, rho_exp) = rho^exp / (rho_mod + rho^exp) that turns thickness
// into intensity in [0, 1).
float foamIntensity(float rho, float rhoMod, float rhoExp) {
  float grown = pow(max(rho, 0.0), rhoExp);
  return grown / (rhoMod + grown);
}

// The radical inverse of `index` in `base`: the Halton sequence's coordinate for that base.
float radicalInverse(uint index, uint base) {
  float inverseBase = 1.0 / float(base);
  float digitWeight = inverseBase;
  float result = 0.0;
  while (index > 0u) {
    result += digitWeight * float(index % base);
    index /= base;
    digitWeight *= inverseBase;
  }
  return result;
}

// Section 2.4.1: the i-th SSAO sample in the cube [-1, 1]^3, Halton in bases 2, 3, 5 with a constant seed
// (the sequence starts at index 1, as index 0 is the cube's corner).
vec3 haltonCubeSample(uint i) {
  return vec3(radicalInverse(i + 1u, 2u), radicalInverse(i + 1u, 3u), radicalInverse(i + 1u, 5u)) * 2.0 - 1.0;
}
