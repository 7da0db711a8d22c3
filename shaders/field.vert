#version 330 core
// SPDX-License-Identifier: GPL-3.0-or-later
// Body surfaces and lines: position, normal and one scalar per vertex.
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_value;

uniform mat4 u_mvp;        // world -> clip
uniform mat3 u_normal_mat; // world -> view for normals (rotation only)

out vec3 v_normal;
out float v_value;

void main()
{
    gl_Position = u_mvp * vec4(a_pos, 1.0);
    v_normal = u_normal_mat * a_normal;
    v_value = a_value;
}
