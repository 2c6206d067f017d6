// The equilateral triangle around the unit circle: its vertices 2 from the centre, its sides 1 away (sqrt(3)
// rounded down by 8e-9, far inside any margin). A particle drawn as one triangle takes vertex gl_VertexID % 3
// of it, mapped onto what it must cover (an ellipsoid's projected ellipse, a foam sprite's disc): llvmpipe
// pays per triangle and per instance, not per vertex (docs/frame-cost.md).
const vec2 kAroundUnitCircle[3] = vec2[3](vec2(0.0, 2.0), vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0));
