#version 410 core
// The renders anyone can check (mipgloss render --aov): per pixel, the direction the environment
// is read at (after the environment's rotation, i.e. in the frame of the baked faces), the Phong
// exponent of the lobe the pixel shows, and whether the pixel is meant to equal that lobe at that
// direction. The lookup mirrors object.frag.
in vec3 vWorldPosition;
in vec3 vNormal;

uniform samplerCube uEnvironment;
uniform samplerCube uIrradiance;
uniform samplerCube uLobe;
uniform vec3 uCameraPosition;
uniform mat3 uEnvironmentRotation;
uniform int uLookup;
uniform bool uUseLobe;
uniform bool uLobeExact;       // the lobe cube holds the lobe at full width
uniform bool uSharperAtGrazing;
uniform float uExponent;       // the lobe the material means (+inf for a mirror)

layout(location = 0) out vec4 aovDirection;  // xyz: unit direction, w: exponent
layout(location = 1) out vec4 aovExact;      // x: 1 exact, 0 not

void main() {
    vec3 n = normalize(vNormal);
    vec3 v = normalize(uCameraPosition - vWorldPosition);
    if (!gl_FrontFacing) n = -n;
    vec3 direction = normalize(uEnvironmentRotation * (uLookup == LOOKUP_REFLECT ? reflect(-v, n) : n));
    float exponent = uLookup == LOOKUP_IRRADIANCE ? 1.0 : uExponent;
    // Exact where the value is one lobe read at one direction with no footprint widening it:
    // from the lobe cube (or the irradiance map, or the mirror level) with the GPU reading its
    // base level (footprint LOD <= 0), never through the grazing option's per-fragment blend.
    bool exact = false;
    if (uLookup == LOOKUP_IRRADIANCE) {
        exact = textureQueryLod(uIrradiance, direction).y <= 0.0;
    } else if (!uSharperAtGrazing) {
        if (uUseLobe)
            exact = uLobeExact && textureQueryLod(uLobe, direction).y <= 0.0;
        else if (isinf(exponent))
            exact = textureQueryLod(uEnvironment, direction).y <= 0.0;
    }
    aovDirection = vec4(direction, exponent);
    aovExact = vec4(exact ? 1.0 : 0.0, 0.0, 0.0, 1.0);
}
