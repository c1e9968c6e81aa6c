/* SPDX-License-Identifier: MIT */
/* Subdivide an ellipse given by 8 exact samples (points and normals) and
 * check that every new point lies on the ellipse; then show how an error
 * is reported. Build: see docs/library.md. */
#include <math.h>
#include <stdio.h>

#include <conica/subdiv.h>

int main(void)
{
    const double pi = acos(-1.0);
    double xy[16], nxy[16];
    for (int i = 0; i < 8; i++) {
        double t = 2.0 * pi * i / 8.0;
        xy[2 * i] = 3.0 * cos(t);        /* the ellipse x^2/9 + y^2/4 = 1 */
        xy[2 * i + 1] = 2.0 * sin(t);
        nxy[2 * i] = cos(t) / 3.0;       /* its gradient: need not be unit */
        nxy[2 * i + 1] = sin(t) / 2.0;
    }

    conica_curve in, out;
    conica_curve_init(&in);
    conica_curve_init(&out);
    conica_subdiv_info info;
    conica_subdiv_info_init(&info);
    conica_status st;
    int rc = 1;

    if (conica_curve_set(xy, nxy, 8, /*closed=*/1, &in, &st) != CONICA_OK) {
        fprintf(stderr, "conica_curve_set: %s\n", st.message);
        goto done;
    }
    conica_subdiv_settings s = conica_subdiv_defaults();
    s.levels = 5;
    if (conica_subdivide(&in, &s, &out, &info, &st) != CONICA_OK) {
        fprintf(stderr, "conica_subdivide: %s\n", st.message);
        goto done;
    }
    double worst = 0.0;
    for (size_t i = 0; i < out.n; i++) {
        double x = out.xy[2 * i], y = out.xy[2 * i + 1];
        double f = fabs(x * x / 9.0 + y * y / 4.0 - 1.0);
        if (f > worst)
            worst = f;
    }
    printf("%zu points -> %zu points, %zu inflection points inserted\n", in.n, out.n,
           info.inflections);
    printf("every point on the ellipse to 1e-12: %s\n", worst < 1e-12 ? "yes" : "no");

    /* A repeated point is an error; the output is left untouched. */
    double bad[6] = {0, 0, 1, 0, 1, 0};
    conica_curve_set(bad, NULL, 3, 1, &in, NULL);
    if (conica_subdivide(&in, &s, &out, NULL, &st) != CONICA_OK)
        printf("error (%s): %s\n", conica_strerror(st.code), st.message);
    rc = worst < 1e-12 ? 0 : 1;
done:
    conica_subdiv_info_free(&info);
    conica_curve_free(&in);
    conica_curve_free(&out);
    return rc;
}
