// tm_state.glsl - partial sums carried from one dispatch of a t_m pass to the next.
//
// Lavapipe ends any shader invocation after 65,535 loop iterations in total (see
// docs/lavapipe.md), so long sums are split over several dispatches: each one resumes from the
// saved compensated sum and saves it again, and always writes its current total to t_m.
#ifndef JADE_TM_STATE_GLSL
#define JADE_TM_STATE_GLSL

// The including shader defines TM_STATE_BINDING, the first of the three bindings used here.
layout(binding = TM_STATE_BINDING, scalar) buffer PartialSum { vec3 partial_sum[]; };
layout(binding = TM_STATE_BINDING + 1, scalar) buffer PartialComp { vec3 partial_comp[]; };
layout(binding = TM_STATE_BINDING + 2, scalar) writeonly buffer Tm { vec3 tm[]; };

void save_partial(uint slot, uint vertex, vec3 sum, vec3 comp)
{
    partial_sum[slot] = sum;
    partial_comp[slot] = comp;
    vec3 t = sum + comp;
    tm[vertex] = CHANNELS == 1u ? vec3(t.x) : t;
}

#endif
