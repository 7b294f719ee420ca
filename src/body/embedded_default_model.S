/* The default body models (assets/body_{female,male,neutral}.npz) as bytes in .rodata.
   SG_MODEL_{FEMALE,MALE,NEUTRAL}_PATH are absolute paths, passed by src/body/CMakeLists.txt. */
    .section .rodata.sg_default_models, "a", @progbits

    .balign 16
    .globl sg_model_female_begin
    .globl sg_model_female_end
sg_model_female_begin:
    .incbin SG_MODEL_FEMALE_PATH
sg_model_female_end:
    .byte 0

    .balign 16
    .globl sg_model_male_begin
    .globl sg_model_male_end
sg_model_male_begin:
    .incbin SG_MODEL_MALE_PATH
sg_model_male_end:
    .byte 0

    .balign 16
    .globl sg_model_neutral_begin
    .globl sg_model_neutral_end
sg_model_neutral_begin:
    .incbin SG_MODEL_NEUTRAL_PATH
sg_model_neutral_end:
    .byte 0

    .section .note.GNU-stack, "", @progbits
