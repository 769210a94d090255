#version 410 core
// The environment seen through the camera, at its own blur: the background's λ means a lobe as a
// material's does; its lobe cube once made, the chain level standing in for it before.
in vec2 vNdc;

uniform samplerCube uEnvironment;
uniform samplerCube uLobe;
uniform bool uUseLobe;
uniform mat4 uInverseViewProjection;  // of the camera's rotation only (the sky is at infinity)
uniform mat3 uEnvironmentRotation;
uniform float uLod;

layout(location = 0) out vec4 fragColour;

void main() {
    vec4 p = uInverseViewProjection * vec4(vNdc, 1.0, 1.0);
    vec3 direction = uEnvironmentRotation * normalize(p.xyz / p.w);
    vec3 colour = uUseLobe ? textureLod(uLobe, direction, 0.0).rgb : textureLod(uEnvironment, direction, uLod).rgb;
    fragColour = vec4(colour, 1.0);
}
