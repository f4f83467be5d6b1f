"""File formats: each reads a model file into a document (every number with its dimension and address).

One module per format, each with one line in
:data:`pitheorem.engines.registry.FORMATS`: ``mjcf`` (MuJoCo's XML, read
through MuJoCo's own parser) and ``urdf`` (read as XML by its
specification); ``numbers`` checks the numbers of any XML model file
before a parser reads them.  A format knows no engine's runs: a runner of
:mod:`pitheorem.engines.runners` compiles its document.  (The package is
``fileformats``, not ``formats``, because ``engines.formats()`` is the
public function that lists them.)
"""
