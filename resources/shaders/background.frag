#version 410 core
// The environment seen through the camera, at its own blur level.
in vec2 vNdc;

uniform samplerCube uEnvironment;
uniform mat4 uInverseViewProjection;  // of the camera's rotation only (the sky is at infinity)
uniform mat3 uEnvironmentRotation;
uniform float uLod;

layout(location = 0) out vec4 fragColour;

void main() {
    vec4 p = uInverseViewProjection * vec4(vNdc, 1.0, 1.0);
    vec3 direction = uEnvironmentRotation * normalize(p.xyz / p.w);
    fragColour = vec4(textureLod(uEnvironment, direction, uLod).rgb, 1.0);
}
