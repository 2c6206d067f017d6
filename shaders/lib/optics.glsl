// Fresnel and refraction at a liquid surface.

// Schlick's approximation of the Fresnel reflectance for the cosine of the angle on the denser side when
// leaving (exiting = true) or the incident side when entering; F0 from the two indices of refraction.
float schlickFresnel(float cosine, float indexRatio) {
  float f0 = (indexRatio - 1.0) / (indexRatio + 1.0);
  f0 *= f0;
  float c = 1.0 - clamp(cosine, 0.0, 1.0);
  return f0 + (1.0 - f0) * c * c * c * c * c;
}
