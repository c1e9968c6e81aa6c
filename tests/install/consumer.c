/* SPDX-License-Identifier: MIT */
/* A program outside the project, built against the INSTALLED library via
 * `pkg-config conica` (tests/cli/install.sh): proves that `make install`
 * ships usable headers, libraries and conica.pc. It subdivides a hexagon
 * sampled from the unit circle and checks every new point lies on it. */
#include <math.h>
#include <stdio.h>

#include <conica/subdiv.h>

int main(void)
{
    double xy[12], nxy[12];
    conica_curve in, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    double worst = 0.0;

    for (int i = 0; i < 6; i++) {
        double t = 2.0 * acos(-1.0) * i / 6.0;
        xy[2 * i] = nxy[2 * i] = cos(t);
        xy[2 * i + 1] = nxy[2 * i + 1] = sin(t);
    }
    conica_curve_init(&in);
    conica_curve_init(&out);
    if (conica_curve_set(xy, nxy, 6, 1, &in, &st) != CONICA_OK)
        return fprintf(stderr, "set: %s\n", st.message), 1;
    s.levels = 4;
    if (conica_subdivide(&in, &s, &out, NULL, &st) != CONICA_OK)
        return fprintf(stderr, "subdivide: %s\n", st.message), 1;
    for (size_t i = 0; i < out.n; i++) {
        double r = hypot(out.xy[2 * i], out.xy[2 * i + 1]);
        if (fabs(r - 1.0) > worst)
            worst = fabs(r - 1.0);
    }
    size_t n = out.n;
    printf("conica %s: %zu points, max radial error %.3g\n", conica_version(), n, worst);
    conica_curve_free(&in);
    conica_curve_free(&out);
    return n == 96 && worst < 1e-12 ? 0 : 1;
}
