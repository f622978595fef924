"""The tiling families: one facade module per family, each registered with :mod:`tilesolve.family`.

=================  ===============================================================================
module             family
=================  ===============================================================================
``dappled``        dappled tilings (the dappled paper)
``board``          Wang tilings of boards, brick Wang tiles and any tile set (brick paper)
``walls``          brick walls, the board family's wall routes (dappled paper §4; 004 §4.3, App. A)
``packing``        tile packings and their counts (class notes §5.5)
``stochastic``     stochastic Wang and corner tilings, the ``wang`` family (class notes ch. 3)
``aperiodic``      aperiodicity checks of Wang tile sets (class notes Part II §8.2)
=================  ===============================================================================

Beside them live the helpers that call a facade: ``packing_search`` (the packing family's
search strategies), ``wall_render`` (wall pictures and maps through the board family) and
``crosscheck_windows`` (the wall and stochastic windows checked against the board family).
Nothing here is imported until a family is used: the registry loads each family through its
entry point (``[project.entry-points."tilesolve.families"]`` in ``pyproject.toml``).
"""
