"""Commands that write pictures: ``draw`` (the mechanism, or the exam's figure),
``plot`` (quantities against the driver or a parameter, a vibration's response),
``animate`` (a GIF of the motion).  matplotlib is imported only when they run."""
from __future__ import annotations

import click

from linkcli.cli.loading import load
from linkcli.cli.options import K_OPTION, METHODS, PICTURE_OPTION
from linkcli.cli.output import not_an_input
from linkcli.errors import InputError


@click.command()
@click.argument("file")
@click.option("--sweep", default=None, metavar="FROM:TO:STEPS",
              help="Driver values FROM to TO (the file's units) in STEPS intervals.")
@click.option("--frf", default=None, metavar="FROM:TO:STEPS",
              help="Vibrations: amplitude and phase against the forcing frequency Omega.")
@click.option("--modes", is_flag=True, help="Vibrations: the mode shapes on the mechanism.")
@click.option("--free", default=None, metavar="0:T:STEPS",
              help="Vibrations: free response from 'initial', linear and nonlinear (s).")
@click.option("--vary", default=None, metavar="NAME=FROM:TO:STEPS",
              help="Answers against a parameter of 'params' (any file, vibrations too).")
@click.option("--clutch", is_flag=True, help="A clutch problem: the two shafts' speeds in time.")
@click.option("--motion", default=None, metavar="0:T:STEPS",
              help="Machines: the driver's speed and motion in time from the file's start "
                   "state (T in the file's time unit).")
@click.option("--regime", is_flag=True, help="Machines: the speed over a cycle of the periodic "
              "regime and the turning-moment diagram with the areas that size the flywheel.")
@click.option("--y", "names", multiple=True, metavar="NAME",
              help="A quantity of the report (repeat for more panels), e.g. --y c --y cdot; "
                   "with --frf or --free, coordinates (default: every free one).")
@K_OPTION
@PICTURE_OPTION
def plot(file, sweep, frf, modes, free, vary, motion, regime, clutch, names, k, output):
    """Plot quantities of FILE against the driver, or a vibration problem's response.

    \b
    Examples:
      linkcli plot mechanisms/polimi-crank-slider.yaml --sweep 0:360:360 --y c --y beta -o pos.png
      linkcli plot mechanisms/fourbar-inverse-dynamics.yaml --sweep 0:360:360 --y Mm -o mm.png
      linkcli plot mechanisms/polimi-2001-09-18-vibration.yaml --modes -o modes.png
      linkcli plot mechanisms/polimi-2001-09-18-vibration.yaml --vary ks=50:150:50 --y w1 -o w.png
      linkcli plot mechanisms/khurmi-16-12-engine-and-machine-torques.yaml --regime -o tm.png
      linkcli plot mechanisms/bhandari-11-14-clutch-energy.yaml --clutch -o speeds.png
      linkcli plot mechanisms/jee-main-disc-string-revolutions.yaml --motion 0:2:200 -o w.png
    """
    chosen = [flag for flag, value in (("--sweep", sweep), ("--frf", frf), ("--modes", modes),
                                       ("--free", free), ("--vary", vary),
                                       ("--motion", motion), ("--regime", regime),
                                       ("--clutch", clutch)) if value]
    if len(chosen) != 1:
        raise InputError("give one of --sweep, --frf, --modes, --free, --vary, --motion, "
                         "--regime, --clutch", key="plot", hint="--sweep FROM:TO:STEPS --y NAME for a "
                         "mechanism with a driver")
    not_an_input(output, file)
    mech = load(file, k, designed=not vary, clutch=True if clutch else "plot against a driver")
    if clutch:
        if mech.clutch is None:
            raise InputError("--clutch draws a clutch problem's speeds (a file with shafts: "
                             "and clutch:)", file=file, key="--clutch",
                             hint="--sweep FROM:TO:STEPS --y NAME for a mechanism")
        from linkcli.pictures.clutch import speeds
        speeds(mech, output)
        return
    if motion:
        from linkcli.pictures.motion import motion as draw_motion
        draw_motion(mech, motion, output)
        return
    if regime:
        from linkcli.pictures.regime import plot_regime
        plot_regime(mech, output)
        return
    if vary:
        from linkcli.pictures.plotting import plot_vary
        plot_vary(mech, vary, list(names), output)
        return
    if sweep:
        from linkcli.runs.limits.names import sweep_names
        from linkcli.pictures.plotting import plot as make
        make(mech, sweep, sweep_names(mech, list(names), key="--y"), output)
        return
    from linkcli.pictures import vibration as pictures
    if frf:
        pictures.frf(mech, frf, list(names), output)
    elif free:
        pictures.free(mech, free, list(names), output)
    else:
        pictures.modes(mech, output)


@click.command()
@click.argument("file")
@K_OPTION
@PICTURE_OPTION
@click.option("--exam", is_flag=True, help="The exam's figure: the data only, no answer.")
@click.option("--lang", type=click.Choice(["it", "en"]), default="en", show_default=True,
              help="Numbers of --exam with a decimal comma (it) or point (en).")
@click.option("--method", type=click.Choice(METHODS), default="closed",
              show_default=True, help="How positions (and loads) are solved: newton for a "
              "class-III group.")
def draw(file, k, output, exam, lang, method):
    """Draw FILE at its driver value: links, sliders, pivots, the vector polygon z_i, loads.

    With --exam, the figure of the exam's statement instead: the mechanism with its data
    (lengths, guides, known loads, the driver's value and sense), nothing solved.

    \b
    Examples:
      linkcli draw mechanisms/padova-2020-07.yaml -o mechanism.png
      linkcli draw mechanisms/padova-2020-07.yaml --exam --lang it -o esame.png
    """
    not_an_input(output, file)
    if exam:
        from linkcli.pictures.exam import draw_exam
        # the problem as asked: a design question's unknowns are not drawn solved
        draw_exam(load(file, k, designed=False, clutch="draw"), output, lang=lang, method=method)
        return
    from linkcli.pictures.plotting import draw as make
    make(load(file, k, clutch="draw"), output, method=method)


@click.command()
@click.argument("file")
@click.option("--sweep", default=None, metavar="FROM:TO:STEPS",
              help="Driver values (the file's units); default a full turn in 72 frames.")
@click.option("--fps", type=click.IntRange(1, 60), default=12, show_default=True)
@K_OPTION
@click.option("-o", "--output", required=True, help="Animated GIF to write.")
def animate(file, sweep, fps, k, output):
    """Animate the motion of FILE over a sweep of the driver (GIF).

    \b
    Examples:
      linkcli animate mechanisms/polimi-crank-slider.yaml -o motion.gif
      linkcli animate mechanisms/padova-2020-07.yaml --sweep 120:140:20 -o lift.gif
    """
    from linkcli.pictures.plotting import animate as make
    not_an_input(output, file)
    make(load(file, k, clutch="animate"), output, sweep, fps)
