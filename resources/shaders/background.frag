#version 410 core
// The environment seen through the camera, at its own blur: the background's λ means a lobe as a
// material's does; the lobe stack's exact lobe where it holds it, the chain level standing in
// for it before.
in vec2 vNdc;

uniform samplerCube uEnvironment;
uniform bool uUseStack;
uniform float uExponent;
uniform mat4 uInverseViewProjection;  // of the camera's rotation only (the sky is at infinity)
uniform mat3 uEnvironmentRotation;
uniform float uLod;

#include "lobe_stack.glsl"

layout(location = 0) out vec4 fragColour;

void main() {
    vec4 p = uInverseViewProjection * vec4(vNdc, 1.0, 1.0);
    vec3 direction = normalize(uEnvironmentRotation * normalize(p.xyz / p.w));
    bool complete;
    float shown = footprintLimitedExponent(uExponent, dFdx(direction), dFdy(direction), complete);
    vec3 colour = uUseStack && stackHolds(shown) ? stackRead(direction, shown)
                                                 : textureLod(uEnvironment, direction, uLod).rgb;
    fragColour = vec4(colour, 1.0);
}
