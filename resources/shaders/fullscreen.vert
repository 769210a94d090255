#version 410 core
// One triangle that covers the screen, from gl_VertexID alone (no vertex buffer). At depth 1 (the
// far plane) so the background is drawn only where no object is.
out vec2 vNdc;

void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
    vNdc = p;
    gl_Position = vec4(p, 1.0, 1.0);
}
