// tm_state.glsl - partial sums carried from one dispatch of a t_m pass to the next.
//
// Lavapipe ends any shader invocation after 65,535 loop iterations in total (see
// docs/lavapipe.md), so long sums are split over several dispatches: each one resumes from the
// saved compensated sum and saves it again, and always writes its current total to t_m.
#ifndef JADE_TM_STATE_GLSL
#define JADE_TM_STATE_GLSL

// The including shader defines TM_STATE_BINDING, the first of the four bindings used here.
layout(binding = TM_STATE_BINDING, scalar) buffer PartialSum { vec3 partial_sum[]; };
layout(binding = TM_STATE_BINDING + 1, scalar) buffer PartialComp { vec3 partial_comp[]; };
layout(binding = TM_STATE_BINDING + 2, scalar) writeonly buffer Tm { vec3 tm[]; };
// Per bake vertex and channel c, at 3·vertex + c: N_c = ∫R_c(|x − s|)(1 − A_o(s))·n(s) dS, the
// normal-weighted t_m (jade/bake.hpp BakeResult::scattering_normal and normal_spread come
// from it), summed plainly: it is needed to ~1e-3. The near pass starts it, the far passes
// add to it. A grey material's channel 0 is copied to the others.
layout(binding = TM_STATE_BINDING + 3, scalar) buffer NormalSum { vec3 normal_sum[]; };

void start_normal_sums(uint vertex, vec3 n[3])
{
    [[unroll]] for (uint c = 0u; c < 3u; ++c) normal_sum[3u * vertex + c] = n[CHANNELS == 1u ? 0u : c];
}
void add_normal_sums(uint vertex, vec3 n[3])
{
    [[unroll]] for (uint c = 0u; c < 3u; ++c) normal_sum[3u * vertex + c] += n[CHANNELS == 1u ? 0u : c];
}

void save_partial(uint slot, uint vertex, vec3 sum, vec3 comp)
{
    partial_sum[slot] = sum;
    partial_comp[slot] = comp;
    vec3 t = sum + comp;
    tm[vertex] = CHANNELS == 1u ? vec3(t.x) : t;
}

// n[c] += v[c]·direction for the baked channels.
void add_weighted(inout vec3 n[3], vec3 v, vec3 direction)
{
    [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) n[c] += v[c] * direction;
}

#endif
