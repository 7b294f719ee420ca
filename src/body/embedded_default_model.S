/* The default body model (assets/default_body.npz) as bytes in .rodata.
   SG_DEFAULT_MODEL_PATH is the absolute path, passed by src/body/CMakeLists.txt. */
    .section .rodata.sg_default_model, "a", @progbits
    .balign 16
    .globl sg_default_model_begin
    .globl sg_default_model_end
sg_default_model_begin:
    .incbin SG_DEFAULT_MODEL_PATH
sg_default_model_end:
    .byte 0

    .section .note.GNU-stack, "", @progbits
