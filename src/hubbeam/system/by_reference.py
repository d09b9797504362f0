"""Passing a compiled value by reference between numba functions.

numba passes a tuple argument to a compiled function that it does not inline field by field:
a system's model (:class:`hubbeam.system.equations.SystemModel`, a tuple of the parts' packs
and the context, some 60 arrays of 7 to 9 words each) costs some 550 words stored by the caller
and read back by the callee on every call. The time loop calls the system's equations two to
three times a step, so that on a small model (exp1 on 4 modes, about 6 us a step) the copies
were 0.4-0.6 us of it (``python benchmarks/loop_profile.py``). :func:`address_of` puts a value
in a slot of the caller's frame once and gives its address; :func:`held_at` reads the value
back in the callee, where LLVM loads only the fields that are read.

The address is valid while the caller's frame is: take it in the function that calls, and
never keep it beyond that call. :func:`address_of` counts no reference (the value stays owned
by the caller, which holds it for as long as the callee runs); :func:`held_at` gives a new
reference where the function that calls it counts references (its code releases each value it
holds when done with it) and none in a function compiled without (``_nrt=False``, as the
system's equations in the time loop).
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def address_of(typingctx, value):
    """A pointer to a copy of ``value`` in the calling function's frame (``types.CPointer``)."""

    def codegen(context, builder, signature, args):
        model = context.data_model_manager[signature.args[0]]  # in memory a bool is a byte, in a register a bit
        slot = cgutils.alloca_once(builder, model.get_data_type())
        builder.store(model.as_data(builder, args[0]), slot)
        return slot

    return types.CPointer(value)(value), codegen


@intrinsic
def held_at(typingctx, pointer):
    """The value at ``pointer`` (from :func:`address_of` in a caller)."""
    if not isinstance(pointer, types.CPointer):
        return None

    def codegen(context, builder, signature, args):
        value = context.data_model_manager[signature.return_type].load_from_data_pointer(builder, args[0])
        if context.enable_nrt:  # a new reference, which the caller's code releases when done with it
            context.nrt.incref(builder, signature.return_type, value)
        return value

    return pointer.dtype(pointer), codegen
