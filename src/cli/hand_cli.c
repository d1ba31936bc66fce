/* The hand-swung chain's options of whirl stability and whirl windows (hand_cli.h). */
#include "cli/hand_cli.h"

void hand_cli_defaults(hand_cli *h, const cli_units *units)
{
    *h = (hand_cli){0};
    h->side = 1;
    h->air = (cli_air)CLI_AIR_INIT(*units);
}

int hand_cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts,
                   size_t nopts, hand_cli *h)
{
    const int rc = cli_parse(cmd, argc, argv, opts, nopts, NULL, 0);
    if (rc) return rc;
    return cli_drag_apply(cmd, &h->air, &h->drag2);
}

int hand_cli_given(const hand_cli *h)
{
    return h->eps_given || h->drag_given || h->drag2_given || h->side_given;
}

int hand_cli_check(const cli_command *cmd, const hand_cli *h)
{
    if (h->side != 1 && h->side != -1)
        return cli_error(cmd, "--side must be 1 or -1, got %d", h->side);
    if (h->eps == 0 && (h->drag > 0 || h->drag2 > 0))
        return cli_error(cmd, "air drag needs --eps > 0 (with the pivot on the axis only the "
                         "hanging chain is steady)");
    return 0;
}
