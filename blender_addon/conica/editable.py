# SPDX-License-Identifier: GPL-3.0-or-later
# Which objects' data the operators may write, as Blender's own edit
# operators decide it (editmode_toggle_poll, BKE_id_is_editable): not data
# linked from a library (id.library), and not the data of a library
# override (the override keeps only overridable properties; geometry
# written into it would be lost on reload, and an override's data is often
# still linked). The message names the data-block and the library file.
# Called by operators.py; reads bpy ID properties only.

# Blender's own poll message for such objects (ED_operator_object_active_editable_ex).
CANNOT_EDIT = "Cannot edit library linked or non-editable override data"


def _library_path(idb):
    lib = idb.library
    if lib is None and idb.override_library is not None:
        ref = idb.override_library.reference
        lib = ref.library if ref is not None else None
    return lib.filepath if lib is not None else "?"


def locked_reason(ob, what="curve"):
    """None when ob's data may be written, else a sentence in Blender's
    words naming the data-block and its library."""
    data = ob.data
    if data is None:
        return None
    if data.library is not None:
        return "%s: %s '%s' is linked from %s" % (CANNOT_EDIT, what, data.name,
                                                  _library_path(data))
    if getattr(data, "override_library", None) is not None:
        return "%s: %s '%s' is a library override of %s" % (CANNOT_EDIT, what, data.name,
                                                            _library_path(data))
    if getattr(data, "is_editable", True) is False:  # Blender 4.x's own test
        return "%s: %s '%s' is not editable" % (CANNOT_EDIT, what, data.name)
    return None


def poll_editable(cls, objs, what="curve"):
    """poll() helper: True when one of objs may be written; else False with
    Blender's poll message naming the first one's library."""
    first = None
    for ob in objs:
        why = locked_reason(ob, what)
        if why is None:
            return True
        first = first or why
    if first is not None and hasattr(cls, "poll_message_set"):
        cls.poll_message_set(first)
    return False
