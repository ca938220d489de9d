// gbuffer (fragment stage, visibility method): the closest surface's gbuffer.cull list entry into
// gbuffer.visibility (R32_UINT, cleared to kNoInstance = sky).
#version 460

layout(location = 0) flat in uint in_entry;
layout(location = 0) out uint out_visibility;

void main() { out_visibility = in_entry; }
