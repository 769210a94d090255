#version 410 core
// The selected object's outline (Renderer::setHighlightedObject): the object pushed outward along
// its normal by uWidthPixels on screen. With uWidthPixels 0 it is the object itself (the stencil
// pass that marks its silhouette).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;
uniform vec2 uViewportSize;  // pixels
uniform float uWidthPixels;

void main() {
    vec4 clip = uViewProjection * (uModel * vec4(aPosition, 1.0));
    vec2 screenNormal = (uViewProjection * vec4(uNormalMatrix * aNormal, 0.0)).xy;
    float len = length(screenNormal);
    // Clip-space offset: pixels × 2 / size in NDC, times w to survive the perspective divide.
    if (len > 1e-8) clip.xy += screenNormal / len * (2.0 * uWidthPixels / uViewportSize) * clip.w;
    gl_Position = clip;
}
