/* SPDX-License-Identifier: MIT */
/* The XML limit flags shared by svgsmooth and scadprofile (svg_cli.h). */
#include "svg_cli.h"

#include <string.h>

#include "cli.h"

/* The largest value a limit flag takes (the document loader refuses
 * documents over 2 GiB anyway). */
#define SVG_CLI_LIMIT_MAX 0x7fffffffL

int conica_svg__cli_limit(const char *prog, const char *flag, const char *value,
                          conica_svg_limits *lim)
{
    size_t *dst;
    long x;
    if (!strcmp(flag, "--max-input-bytes"))
        dst = &lim->max_bytes;
    else if (!strcmp(flag, "--max-depth"))
        dst = &lim->max_depth;
    else if (!strcmp(flag, "--max-elements"))
        dst = &lim->max_elements;
    else if (!strcmp(flag, "--max-path-bytes"))
        dst = &lim->max_path_bytes;
    else if (!strcmp(flag, "--max-attributes"))
        dst = &lim->max_attributes;
    else if (!strcmp(flag, "--max-namespaces"))
        dst = &lim->max_namespaces;
    else
        return 0;
    if (!value || cli_parse_int(value, 1, SVG_CLI_LIMIT_MAX, &x)) {
        cli_usage_error(prog, "%s needs a whole number in 1..%ld, not '%s'", flag,
                        SVG_CLI_LIMIT_MAX, value ? value : "");
        return -1;
    }
    *dst = (size_t)x;
    return 1;
}
