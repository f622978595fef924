"""``tilesolve studio``: a local web page over the family registry (DESIGN.md, "studio/").

The page (``static/``) builds each family's form from :class:`tilesolve.family.Form`, so
every registered family with a form is reachable without a special case; the server
(:mod:`tilesolve.studio.app`) solves in worker processes (:mod:`tilesolve.studio.jobs`) so
that a long search can be cancelled and never blocks other requests.
"""
