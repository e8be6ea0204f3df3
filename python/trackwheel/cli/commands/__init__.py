"""The sub-commands of ``trackwheel``, one module each: ``add(sub)`` adds its parser (its
options, help and description), ``run(args, parser)`` runs it and returns the exit code.
A new command is a new module here, listed in :data:`COMMANDS`."""

from . import decay_rate, eigen, periodic, receptance, reproduce, run, settle, sweep

#: the sub-commands in the order ``trackwheel --help`` lists them
COMMANDS = (reproduce, run, sweep, settle, periodic, eigen, receptance, decay_rate)
