// gbuffer.resolve (vertex stage): one triangle covering the viewport (3 vertices, no inputs).
#version 460
void main() {
  vec2 p = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
