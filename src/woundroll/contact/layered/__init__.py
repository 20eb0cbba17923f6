"""The layered roll: discrete web layers with Coulomb friction between them under the head,
the continuum roll below (:mod:`woundroll.contact.layered.solver`)."""
