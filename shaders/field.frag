#version 330 core
// SPDX-License-Identifier: GPL-3.0-or-later
// The scalar is interpolated and only then mapped to a colour (a 1D
// colormap texture), so colours between vertices stay on the colormap.
in vec3 v_normal;
in float v_value;

uniform sampler2D u_cmap;   // 256 x 1 RGBA colormap
uniform vec2 u_range;       // value at t = 0 and t = 1
uniform int u_mode;         // 0: colormap, 1: flat u_color
uniform vec4 u_color;
uniform int u_lit;          // 0 flat, 1 body (soft), 2 obstacle (shaded)

out vec4 frag;

void main()
{
    vec3 base;
    float alpha = 1.0;
    if (u_mode == 0) {
        float t = clamp((v_value - u_range.x) / (u_range.y - u_range.x), 0.0, 1.0);
        base = texture(u_cmap, vec2((t * 255.0 + 0.5) / 256.0, 0.5)).rgb;
    } else {
        base = u_color.rgb;
        alpha = u_color.a;
    }
    if (u_lit >= 1) {
        vec3 n = normalize(v_normal);
        // two-sided
        if (n.z < 0.0)
            n = -n;
        if (u_lit == 1) {
            // the body: faces towards the viewer in the colour bar's
            // colours, turned faces at most 12 % darker, no highlight, so
            // that a colour is read off any face
            base = base * (0.88 + 0.12 * n.z);
        } else {
            // the obstacle: a headlight and a key light, a highlight
            vec3 l = normalize(vec3(0.35, 0.55, 0.75));
            vec3 h = normalize(l + vec3(0.0, 0.0, 1.0));
            float diff = 0.35 * max(dot(n, l), 0.0) + 0.25 * n.z;
            float spec = 0.12 * pow(max(dot(n, h), 0.0), 40.0);
            base = base * (0.50 + diff) + vec3(spec);
        }
    }
    frag = vec4(base, alpha);
}
