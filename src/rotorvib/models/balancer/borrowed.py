"""Borrowed array views for the integrators' step loops: arrays that carry no reference count.

numba counts the references to every array it passes around, with an atomic add and subtract
on the array's memory record (its meminfo) each time a compiled function binds an array argument,
takes a row view (``K[s]``) or inlines a helper; it removes only the pairs it can prove
redundant, not those around a call that may raise. In the integrators' loops that was about a
hundred atomic pairs per step, the largest cost of a run after the right-hand side (``perf
record`` shows it as ``NRT_incref`` and ``NRT_decref``), and the batch threads contended for the
records of the arrays they share (the tableau). A view made by :func:`borrowed` has no memory
record (a null meminfo), which numba's counting skips after one comparison.

A borrowed view owns nothing: it is valid only while its owner lives. The integrators borrow
their own arguments, which their caller holds for the whole call, and never return a view.
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def borrowed(typingctx, array):
    """A view of ``array`` (same data, shape, strides and type) without a memory record or a
    parent object, so that numba keeps no count of its references."""
    if not isinstance(array, types.Array):
        return None

    def codegen(context, builder, signature, args):
        view = context.make_array(array)(context, builder, value=args[0])
        view.meminfo = cgutils.get_null_value(view.meminfo.type)
        view.parent = cgutils.get_null_value(view.parent.type)
        return view._getvalue()

    return array(array), codegen
