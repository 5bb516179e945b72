#version 300 es
// The value a scattered coefficient adds to its cell (column_scatter.vert);
// the blend unit (ONE, ONE on an RGBA32F target) does the sum.
precision highp float;

flat in vec3 v_value;
out vec4 o_color;

void main() { o_color = vec4(v_value, 0.0); }
