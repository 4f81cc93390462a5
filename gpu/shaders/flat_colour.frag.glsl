#version 450 core
// One uniform colour: the proof that the pipeline draws, and the receiver pass later.
layout(location = 1) uniform vec4 colour;
layout(location = 0) out vec4 fragment;

void main() {
  fragment = colour;
}
