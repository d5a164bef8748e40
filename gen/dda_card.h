/* Host interface of the PCI DDA card: function registers (I/O BAR0, memory BAR2) and more.
 * Generated from rtl/ by python -m rtl.top --convert; do not edit. */
#ifndef DDA_REGISTERS_H
#define DDA_REGISTERS_H

#define DDA_IO_BAR_SIZE 256u

#define DDA_ID 0x00u
#define DDA_ID_RESET 0xDDAC0203u
#define DDA_ID_VERSION_SHIFT 0u
#define DDA_ID_VERSION_MASK 0x0000FFFFu
#define DDA_ID_MAGIC_SHIFT 16u
#define DDA_ID_MAGIC_MASK 0xFFFF0000u

#define DDA_CONTROL 0x04u
#define DDA_CONTROL_RESET 0x00000000u
#define DDA_CONTROL_ENABLE_SHIFT 0u
#define DDA_CONTROL_ENABLE_MASK 0x00000001u
#define DDA_CONTROL_MODE_SHIFT 1u
#define DDA_CONTROL_MODE_MASK 0x00000002u

#define DDA_COMMAND 0x08u
#define DDA_COMMAND_RESET 0x00000000u
#define DDA_COMMAND_SOFT_RESET_SHIFT 0u
#define DDA_COMMAND_SOFT_RESET_MASK 0x00000001u
#define DDA_COMMAND_CLEAR_ERROR_SHIFT 1u
#define DDA_COMMAND_CLEAR_ERROR_MASK 0x00000002u
#define DDA_COMMAND_CLEAR_POSITION_SHIFT 2u
#define DDA_COMMAND_CLEAR_POSITION_MASK 0x00000004u
#define DDA_COMMAND_CLEAR_STOP_SHIFT 3u
#define DDA_COMMAND_CLEAR_STOP_MASK 0x00000008u

#define DDA_STATUS 0x0Cu
#define DDA_STATUS_RESET 0x00000100u
#define DDA_STATUS_BUSY_SHIFT 0u
#define DDA_STATUS_BUSY_MASK 0x00000001u
#define DDA_STATUS_DONE_SHIFT 1u
#define DDA_STATUS_DONE_MASK 0x00000002u
#define DDA_STATUS_QUADRANT_SHIFT 2u
#define DDA_STATUS_QUADRANT_MASK 0x0000000Cu
#define DDA_STATUS_ERROR_SHIFT 4u
#define DDA_STATUS_ERROR_MASK 0x000000F0u
#define DDA_STATUS_FIFO_EMPTY_SHIFT 8u
#define DDA_STATUS_FIFO_EMPTY_MASK 0x00000100u
#define DDA_STATUS_FIFO_FULL_SHIFT 9u
#define DDA_STATUS_FIFO_FULL_MASK 0x00000200u
#define DDA_STATUS_STOPPED_SHIFT 10u
#define DDA_STATUS_STOPPED_MASK 0x00000400u
#define DDA_STATUS_FIFO_LEVEL_SHIFT 16u
#define DDA_STATUS_FIFO_LEVEL_MASK 0xFFFF0000u

#define DDA_INT_ENABLE 0x10u
#define DDA_INT_ENABLE_RESET 0x00000000u
#define DDA_INT_ENABLE_DONE_SHIFT 0u
#define DDA_INT_ENABLE_DONE_MASK 0x00000001u
#define DDA_INT_ENABLE_LOW_WATER_SHIFT 1u
#define DDA_INT_ENABLE_LOW_WATER_MASK 0x00000002u
#define DDA_INT_ENABLE_ERROR_SHIFT 2u
#define DDA_INT_ENABLE_ERROR_MASK 0x00000004u
#define DDA_INT_ENABLE_MARK_SHIFT 3u
#define DDA_INT_ENABLE_MARK_MASK 0x00000008u
#define DDA_INT_ENABLE_CLAMPED_SHIFT 4u
#define DDA_INT_ENABLE_CLAMPED_MASK 0x00000010u
#define DDA_INT_ENABLE_STOPPED_SHIFT 5u
#define DDA_INT_ENABLE_STOPPED_MASK 0x00000020u
#define DDA_INT_ENABLE_INPUT_SHIFT 6u
#define DDA_INT_ENABLE_INPUT_MASK 0x00000040u
#define DDA_INT_ENABLE_HOMED_SHIFT 7u
#define DDA_INT_ENABLE_HOMED_MASK 0x00000080u
#define DDA_INT_ENABLE_INDEX_SHIFT 8u
#define DDA_INT_ENABLE_INDEX_MASK 0x00000100u
#define DDA_INT_ENABLE_PROBE_SHIFT 9u
#define DDA_INT_ENABLE_PROBE_MASK 0x00000200u

#define DDA_INT_STATUS 0x14u
#define DDA_INT_STATUS_RESET 0x00000000u
#define DDA_INT_STATUS_DONE_SHIFT 0u
#define DDA_INT_STATUS_DONE_MASK 0x00000001u
#define DDA_INT_STATUS_LOW_WATER_SHIFT 1u
#define DDA_INT_STATUS_LOW_WATER_MASK 0x00000002u
#define DDA_INT_STATUS_ERROR_SHIFT 2u
#define DDA_INT_STATUS_ERROR_MASK 0x00000004u
#define DDA_INT_STATUS_MARK_SHIFT 3u
#define DDA_INT_STATUS_MARK_MASK 0x00000008u
#define DDA_INT_STATUS_CLAMPED_SHIFT 4u
#define DDA_INT_STATUS_CLAMPED_MASK 0x00000010u
#define DDA_INT_STATUS_STOPPED_SHIFT 5u
#define DDA_INT_STATUS_STOPPED_MASK 0x00000020u
#define DDA_INT_STATUS_INPUT_SHIFT 6u
#define DDA_INT_STATUS_INPUT_MASK 0x00000040u
#define DDA_INT_STATUS_HOMED_SHIFT 7u
#define DDA_INT_STATUS_HOMED_MASK 0x00000080u
#define DDA_INT_STATUS_INDEX_SHIFT 8u
#define DDA_INT_STATUS_INDEX_MASK 0x00000100u
#define DDA_INT_STATUS_PROBE_SHIFT 9u
#define DDA_INT_STATUS_PROBE_MASK 0x00000200u

#define DDA_LOW_WATER 0x18u
#define DDA_LOW_WATER_RESET 0x00000000u
#define DDA_LOW_WATER_LEVEL_SHIFT 0u
#define DDA_LOW_WATER_LEVEL_MASK 0x0000FFFFu
#define DDA_LOW_WATER_MIN (0)
#define DDA_LOW_WATER_MAX (65535)

#define DDA_MARK_TAG 0x1Cu
#define DDA_MARK_TAG_RESET 0x00000000u
#define DDA_MARK_TAG_TAG_SHIFT 0u
#define DDA_MARK_TAG_TAG_MASK 0x0000FFFFu

#define DDA_POS_X 0x20u
#define DDA_POS_X_RESET 0x00000000u
#define DDA_POS_X_STEPS_SHIFT 0u
#define DDA_POS_X_STEPS_MASK 0xFFFFFFFFu

#define DDA_POS_Y 0x24u
#define DDA_POS_Y_RESET 0x00000000u
#define DDA_POS_Y_STEPS_SHIFT 0u
#define DDA_POS_Y_STEPS_MASK 0xFFFFFFFFu

#define DDA_FEED_RATE 0x28u
#define DDA_FEED_RATE_RESET 0x00001000u
#define DDA_FEED_RATE_RATE_SHIFT 0u
#define DDA_FEED_RATE_RATE_MASK 0x0000FFFFu
#define DDA_FEED_RATE_SET_INDEX 0u
#define DDA_FEED_RATE_MIN (1)
#define DDA_FEED_RATE_MAX (32768)

#define DDA_RAMP_START 0x2Cu
#define DDA_RAMP_START_RESET 0x00001000u
#define DDA_RAMP_START_RATE_SHIFT 0u
#define DDA_RAMP_START_RATE_MASK 0x0000FFFFu
#define DDA_RAMP_START_SET_INDEX 1u
#define DDA_RAMP_START_MIN (1)
#define DDA_RAMP_START_MAX (32768)

#define DDA_RAMP_STEP 0x30u
#define DDA_RAMP_STEP_RESET 0x00000000u
#define DDA_RAMP_STEP_STEP_SHIFT 0u
#define DDA_RAMP_STEP_STEP_MASK 0x0000FFFFu
#define DDA_RAMP_STEP_SET_INDEX 2u
#define DDA_RAMP_STEP_MIN (0)
#define DDA_RAMP_STEP_MAX (65535)

#define DDA_STEP_WIDTH 0x34u
#define DDA_STEP_WIDTH_RESET 0x00000001u
#define DDA_STEP_WIDTH_CLOCKS_SHIFT 0u
#define DDA_STEP_WIDTH_CLOCKS_MASK 0x000000FFu
#define DDA_STEP_WIDTH_SET_INDEX 3u
#define DDA_STEP_WIDTH_MIN (1)
#define DDA_STEP_WIDTH_MAX (255)

#define DDA_DIR_SETUP 0x38u
#define DDA_DIR_SETUP_RESET 0x00000001u
#define DDA_DIR_SETUP_CLOCKS_SHIFT 0u
#define DDA_DIR_SETUP_CLOCKS_MASK 0x000000FFu
#define DDA_DIR_SETUP_SET_INDEX 4u
#define DDA_DIR_SETUP_MIN (1)
#define DDA_DIR_SETUP_MAX (255)

#define DDA_DIR_HOLD 0x3Cu
#define DDA_DIR_HOLD_RESET 0x00000001u
#define DDA_DIR_HOLD_CLOCKS_SHIFT 0u
#define DDA_DIR_HOLD_CLOCKS_MASK 0x000000FFu
#define DDA_DIR_HOLD_SET_INDEX 5u
#define DDA_DIR_HOLD_MIN (1)
#define DDA_DIR_HOLD_MAX (255)

#define DDA_DIR_POLARITY 0x40u
#define DDA_DIR_POLARITY_RESET 0x00000000u
#define DDA_DIR_POLARITY_X_SHIFT 0u
#define DDA_DIR_POLARITY_X_MASK 0x00000001u
#define DDA_DIR_POLARITY_Y_SHIFT 1u
#define DDA_DIR_POLARITY_Y_MASK 0x00000002u
#define DDA_DIR_POLARITY_Z_SHIFT 2u
#define DDA_DIR_POLARITY_Z_MASK 0x00000004u
#define DDA_DIR_POLARITY_A_SHIFT 3u
#define DDA_DIR_POLARITY_A_MASK 0x00000008u
#define DDA_DIR_POLARITY_B_SHIFT 4u
#define DDA_DIR_POLARITY_B_MASK 0x00000010u
#define DDA_DIR_POLARITY_C_SHIFT 5u
#define DDA_DIR_POLARITY_C_MASK 0x00000020u

#define DDA_PULSE_PERIOD_X 0x44u
#define DDA_PULSE_PERIOD_X_RESET 0x00000002u
#define DDA_PULSE_PERIOD_X_CLOCKS_SHIFT 0u
#define DDA_PULSE_PERIOD_X_CLOCKS_MASK 0x0000FFFFu
#define DDA_PULSE_PERIOD_X_SET_INDEX 6u
#define DDA_PULSE_PERIOD_X_MIN (1)
#define DDA_PULSE_PERIOD_X_MAX (65535)

#define DDA_PULSE_PERIOD_Y 0x48u
#define DDA_PULSE_PERIOD_Y_RESET 0x00000002u
#define DDA_PULSE_PERIOD_Y_CLOCKS_SHIFT 0u
#define DDA_PULSE_PERIOD_Y_CLOCKS_MASK 0x0000FFFFu
#define DDA_PULSE_PERIOD_Y_SET_INDEX 7u
#define DDA_PULSE_PERIOD_Y_MIN (1)
#define DDA_PULSE_PERIOD_Y_MAX (65535)

#define DDA_PULSE_COUNT_X 0x4Cu
#define DDA_PULSE_COUNT_X_RESET 0x00000000u
#define DDA_PULSE_COUNT_X_COUNT_SHIFT 0u
#define DDA_PULSE_COUNT_X_COUNT_MASK 0x00FFFFFFu
#define DDA_PULSE_COUNT_X_MIN (-8388608)
#define DDA_PULSE_COUNT_X_MAX (8388607)

#define DDA_PULSE_COUNT_Y 0x50u
#define DDA_PULSE_COUNT_Y_RESET 0x00000000u
#define DDA_PULSE_COUNT_Y_COUNT_SHIFT 0u
#define DDA_PULSE_COUNT_Y_COUNT_MASK 0x00FFFFFFu
#define DDA_PULSE_COUNT_Y_MIN (-8388608)
#define DDA_PULSE_COUNT_Y_MAX (8388607)

#define DDA_CLOCK_HZ 0x54u
#define DDA_CLOCK_HZ_RESET 0x01FCA055u
#define DDA_CLOCK_HZ_HZ_SHIFT 0u
#define DDA_CLOCK_HZ_HZ_MASK 0xFFFFFFFFu

#define DDA_FIFO_SIZE 0x58u
#define DDA_FIFO_SIZE_RESET 0x00000200u
#define DDA_FIFO_SIZE_WORDS_SHIFT 0u
#define DDA_FIFO_SIZE_WORDS_MASK 0x0000FFFFu

#define DDA_BUILD 0x5Cu
#define DDA_BUILD_RESET 0x010C0218u
#define DDA_BUILD_COORD_WIDTH_SHIFT 0u
#define DDA_BUILD_COORD_WIDTH_MASK 0x000000FFu
#define DDA_BUILD_AXES_SHIFT 8u
#define DDA_BUILD_AXES_MASK 0x00000F00u
#define DDA_BUILD_DDA_VARIANTS_SHIFT 16u
#define DDA_BUILD_DDA_VARIANTS_MASK 0x000F0000u
#define DDA_BUILD_DEVICE_SHIFT 24u
#define DDA_BUILD_DEVICE_MASK 0x0F000000u
#define DDA_BUILD_ENCODERS_SHIFT 28u
#define DDA_BUILD_ENCODERS_MASK 0x10000000u

#define DDA_MACHINE_CONTROL 0x60u
#define DDA_MACHINE_CONTROL_RESET 0x00000000u
#define DDA_MACHINE_CONTROL_DRIVE_ENABLE_SHIFT 0u
#define DDA_MACHINE_CONTROL_DRIVE_ENABLE_MASK 0x00000001u
#define DDA_MACHINE_CONTROL_HOLD_SHIFT 1u
#define DDA_MACHINE_CONTROL_HOLD_MASK 0x00000002u

#define DDA_MACHINE_STATUS 0x64u
#define DDA_MACHINE_STATUS_RESET 0x00000000u
#define DDA_MACHINE_STATUS_RAW_SHIFT 0u
#define DDA_MACHINE_STATUS_RAW_MASK 0x0000007Fu
#define DDA_MACHINE_STATUS_ACTIVE_SHIFT 8u
#define DDA_MACHINE_STATUS_ACTIVE_MASK 0x00007F00u
#define DDA_MACHINE_STATUS_STOPPED_SHIFT 16u
#define DDA_MACHINE_STATUS_STOPPED_MASK 0x00010000u
#define DDA_MACHINE_STATUS_DRIVE_ENABLE_SHIFT 17u
#define DDA_MACHINE_STATUS_DRIVE_ENABLE_MASK 0x00020000u
#define DDA_MACHINE_STATUS_HELD_SHIFT 18u
#define DDA_MACHINE_STATUS_HELD_MASK 0x00040000u
#define DDA_MACHINE_STATUS_STOPPING_SHIFT 19u
#define DDA_MACHINE_STATUS_STOPPING_MASK 0x00080000u

#define DDA_STOP_REASON 0x68u
#define DDA_STOP_REASON_RESET 0x00000000u
#define DDA_STOP_REASON_REASON_SHIFT 0u
#define DDA_STOP_REASON_REASON_MASK 0x00000007u
#define DDA_STOP_REASON_LIMITS_SHIFT 4u
#define DDA_STOP_REASON_LIMITS_MASK 0x000000F0u
#define DDA_STOP_REASON_AXIS_SHIFT 16u
#define DDA_STOP_REASON_AXIS_MASK 0x00070000u

#define DDA_INPUT_POLARITY 0x6Cu
#define DDA_INPUT_POLARITY_RESET 0x00000000u
#define DDA_INPUT_POLARITY_ESTOP_SHIFT 0u
#define DDA_INPUT_POLARITY_ESTOP_MASK 0x00000001u
#define DDA_INPUT_POLARITY_LIMIT_POS_X_SHIFT 1u
#define DDA_INPUT_POLARITY_LIMIT_POS_X_MASK 0x00000002u
#define DDA_INPUT_POLARITY_LIMIT_NEG_X_SHIFT 2u
#define DDA_INPUT_POLARITY_LIMIT_NEG_X_MASK 0x00000004u
#define DDA_INPUT_POLARITY_LIMIT_POS_Y_SHIFT 3u
#define DDA_INPUT_POLARITY_LIMIT_POS_Y_MASK 0x00000008u
#define DDA_INPUT_POLARITY_LIMIT_NEG_Y_SHIFT 4u
#define DDA_INPUT_POLARITY_LIMIT_NEG_Y_MASK 0x00000010u
#define DDA_INPUT_POLARITY_HOME_X_SHIFT 5u
#define DDA_INPUT_POLARITY_HOME_X_MASK 0x00000020u
#define DDA_INPUT_POLARITY_HOME_Y_SHIFT 6u
#define DDA_INPUT_POLARITY_HOME_Y_MASK 0x00000040u

#define DDA_INPUT_FILTER 0x70u
#define DDA_INPUT_FILTER_RESET 0x00000003u
#define DDA_INPUT_FILTER_SAMPLES_SHIFT 0u
#define DDA_INPUT_FILTER_SAMPLES_MASK 0x0000000Fu
#define DDA_INPUT_FILTER_MIN (1)
#define DDA_INPUT_FILTER_MAX (15)

#define DDA_INPUT_TICK 0x74u
#define DDA_INPUT_TICK_RESET 0x00000001u
#define DDA_INPUT_TICK_CLOCKS_SHIFT 0u
#define DDA_INPUT_TICK_CLOCKS_MASK 0x0000FFFFu
#define DDA_INPUT_TICK_MIN (1)
#define DDA_INPUT_TICK_MAX (65535)

#define DDA_WATCHDOG 0x78u
#define DDA_WATCHDOG_RESET 0x00000000u
#define DDA_WATCHDOG_CLOCKS_SHIFT 0u
#define DDA_WATCHDOG_CLOCKS_MASK 0x00FFFFFFu
#define DDA_WATCHDOG_MIN (0)
#define DDA_WATCHDOG_MAX (16777215)

#define DDA_HOME 0x7Cu
#define DDA_HOME_RESET 0x00000000u
#define DDA_HOME_AXIS_SHIFT 0u
#define DDA_HOME_AXIS_MASK 0x00000001u
#define DDA_HOME_NEGATIVE_SHIFT 1u
#define DDA_HOME_NEGATIVE_MASK 0x00000002u

#define DDA_HOME_STATUS 0x80u
#define DDA_HOME_STATUS_RESET 0x00000000u
#define DDA_HOME_STATUS_BUSY_SHIFT 0u
#define DDA_HOME_STATUS_BUSY_MASK 0x00000001u
#define DDA_HOME_STATUS_DONE_SHIFT 1u
#define DDA_HOME_STATUS_DONE_MASK 0x00000002u
#define DDA_HOME_STATUS_NOT_FOUND_SHIFT 2u
#define DDA_HOME_STATUS_NOT_FOUND_MASK 0x00000004u
#define DDA_HOME_STATUS_REFUSED_SHIFT 3u
#define DDA_HOME_STATUS_REFUSED_MASK 0x00000008u
#define DDA_HOME_STATUS_PHASE_SHIFT 4u
#define DDA_HOME_STATUS_PHASE_MASK 0x00000030u

#define DDA_HOME_SEEK_PERIOD 0x84u
#define DDA_HOME_SEEK_PERIOD_RESET 0x00000064u
#define DDA_HOME_SEEK_PERIOD_CLOCKS_SHIFT 0u
#define DDA_HOME_SEEK_PERIOD_CLOCKS_MASK 0x0000FFFFu
#define DDA_HOME_SEEK_PERIOD_MIN (1)
#define DDA_HOME_SEEK_PERIOD_MAX (65535)

#define DDA_HOME_RELEASE_PERIOD 0x88u
#define DDA_HOME_RELEASE_PERIOD_RESET 0x000003E8u
#define DDA_HOME_RELEASE_PERIOD_CLOCKS_SHIFT 0u
#define DDA_HOME_RELEASE_PERIOD_CLOCKS_MASK 0x0000FFFFu
#define DDA_HOME_RELEASE_PERIOD_MIN (1)
#define DDA_HOME_RELEASE_PERIOD_MAX (65535)

#define DDA_HOME_BACKOFF 0x8Cu
#define DDA_HOME_BACKOFF_RESET 0x00000000u
#define DDA_HOME_BACKOFF_STEPS_SHIFT 0u
#define DDA_HOME_BACKOFF_STEPS_MASK 0x0000FFFFu
#define DDA_HOME_BACKOFF_MIN (0)
#define DDA_HOME_BACKOFF_MAX (65535)

#define DDA_HOME_SEARCH 0x90u
#define DDA_HOME_SEARCH_RESET 0x0000FFFFu
#define DDA_HOME_SEARCH_STEPS_SHIFT 0u
#define DDA_HOME_SEARCH_STEPS_MASK 0x007FFFFFu
#define DDA_HOME_SEARCH_MIN (1)
#define DDA_HOME_SEARCH_MAX (8388607)

#define DDA_STEP_SPACE 0x94u
#define DDA_STEP_SPACE_RESET 0x00000001u
#define DDA_STEP_SPACE_CLOCKS_SHIFT 0u
#define DDA_STEP_SPACE_CLOCKS_MASK 0x000000FFu
#define DDA_STEP_SPACE_SET_INDEX 8u
#define DDA_STEP_SPACE_MIN (1)
#define DDA_STEP_SPACE_MAX (255)

#define DDA_STEP_MODE 0x98u
#define DDA_STEP_MODE_RESET 0x00000000u
#define DDA_STEP_MODE_MODE_SHIFT 0u
#define DDA_STEP_MODE_MODE_MASK 0x00000003u
#define DDA_STEP_MODE_MIN (0)
#define DDA_STEP_MODE_MAX (2)

/* TIMESTAMP: a build with encoders only (DDA_BUILD_ENCODERS) */
#define DDA_TIMESTAMP 0x9Cu
#define DDA_TIMESTAMP_RESET 0x00000000u
#define DDA_TIMESTAMP_CLOCKS_SHIFT 0u
#define DDA_TIMESTAMP_CLOCKS_MASK 0xFFFFFFFFu

/* PROBE_CONTROL: a build with encoders only (DDA_BUILD_ENCODERS) */
#define DDA_PROBE_CONTROL 0xA0u
#define DDA_PROBE_CONTROL_RESET 0x00000200u
#define DDA_PROBE_CONTROL_ARM_SHIFT 0u
#define DDA_PROBE_CONTROL_ARM_MASK 0x00000001u
#define DDA_PROBE_CONTROL_INVERT_SHIFT 1u
#define DDA_PROBE_CONTROL_INVERT_MASK 0x00000002u
#define DDA_PROBE_CONTROL_FILTER_SHIFT 8u
#define DDA_PROBE_CONTROL_FILTER_MASK 0x00000F00u

/* Per-axis register blocks, BAR2 only: axis i (0 X, 1 Y, 2 Z, 3 A, 4 B, 5 C; BUILD.AXES of them)
 * at BLOCK_BASE + STRIDE * i.  X's and Y's hold BAR0's registers where BAR0 has them
 * (POS = POS_X / POS_Y, ...); ENC_* and the rest are the blocks' only (builds with encoders).
 * A read of X's POS captures the other axes' POS: read it first. */
#define DDA_AXIS_BLOCK_BASE 0x100u
#define DDA_AXIS_STRIDE 0x40u
#define DDA_AXIS_BLOCK(axis) (DDA_AXIS_BLOCK_BASE + DDA_AXIS_STRIDE * (unsigned)(axis))

#define DDA_AXIS_POS 0x00u /* inside the block */
#define DDA_AXIS_POS_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_POS)
#define DDA_AXIS_POS_RESET 0x00000000u
#define DDA_AXIS_POS_STEPS_SHIFT 0u
#define DDA_AXIS_POS_STEPS_MASK 0xFFFFFFFFu

#define DDA_AXIS_PULSE_PERIOD 0x04u /* inside the block */
#define DDA_AXIS_PULSE_PERIOD_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_PULSE_PERIOD)
#define DDA_AXIS_PULSE_PERIOD_RESET 0x00000002u
#define DDA_AXIS_PULSE_PERIOD_CLOCKS_SHIFT 0u
#define DDA_AXIS_PULSE_PERIOD_CLOCKS_MASK 0x0000FFFFu
#define DDA_AXIS_PULSE_PERIOD_MIN (1)
#define DDA_AXIS_PULSE_PERIOD_MAX (65535)

#define DDA_AXIS_PULSE_COUNT 0x08u /* inside the block */
#define DDA_AXIS_PULSE_COUNT_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_PULSE_COUNT)
#define DDA_AXIS_PULSE_COUNT_RESET 0x00000000u
#define DDA_AXIS_PULSE_COUNT_COUNT_SHIFT 0u
#define DDA_AXIS_PULSE_COUNT_COUNT_MASK 0x00FFFFFFu
#define DDA_AXIS_PULSE_COUNT_MIN (-8388608)
#define DDA_AXIS_PULSE_COUNT_MAX (8388607)

#define DDA_AXIS_ENC_COUNT 0x10u /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_COUNT_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_COUNT)
#define DDA_AXIS_ENC_COUNT_RESET 0x00000000u
#define DDA_AXIS_ENC_COUNT_COUNT_SHIFT 0u
#define DDA_AXIS_ENC_COUNT_COUNT_MASK 0xFFFFFFFFu

#define DDA_AXIS_ENC_STATUS 0x14u /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_STATUS_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_STATUS)
#define DDA_AXIS_ENC_STATUS_RESET 0x00000000u
#define DDA_AXIS_ENC_STATUS_QUAD_ERROR_SHIFT 0u
#define DDA_AXIS_ENC_STATUS_QUAD_ERROR_MASK 0x00000001u
#define DDA_AXIS_ENC_STATUS_DIRECTION_SHIFT 1u
#define DDA_AXIS_ENC_STATUS_DIRECTION_MASK 0x00000002u
#define DDA_AXIS_ENC_STATUS_ERROR_COUNT_SHIFT 8u
#define DDA_AXIS_ENC_STATUS_ERROR_COUNT_MASK 0x0000FF00u

#define DDA_AXIS_ENC_CONTROL 0x18u /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_CONTROL_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_CONTROL)
#define DDA_AXIS_ENC_CONTROL_RESET 0x00000200u
#define DDA_AXIS_ENC_CONTROL_MODE_SHIFT 0u
#define DDA_AXIS_ENC_CONTROL_MODE_MASK 0x00000001u
#define DDA_AXIS_ENC_CONTROL_INDEX_ZERO_SHIFT 1u
#define DDA_AXIS_ENC_CONTROL_INDEX_ZERO_MASK 0x00000002u
#define DDA_AXIS_ENC_CONTROL_INDEX_ARM_SHIFT 2u
#define DDA_AXIS_ENC_CONTROL_INDEX_ARM_MASK 0x00000004u
#define DDA_AXIS_ENC_CONTROL_POLARITY_SHIFT 4u
#define DDA_AXIS_ENC_CONTROL_POLARITY_MASK 0x00000070u
#define DDA_AXIS_ENC_CONTROL_FILTER_SHIFT 8u
#define DDA_AXIS_ENC_CONTROL_FILTER_MASK 0x00000F00u

#define DDA_AXIS_ENC_INDEX_LATCH 0x1Cu /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_INDEX_LATCH_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_INDEX_LATCH)
#define DDA_AXIS_ENC_INDEX_LATCH_RESET 0x00000000u
#define DDA_AXIS_ENC_INDEX_LATCH_COUNT_SHIFT 0u
#define DDA_AXIS_ENC_INDEX_LATCH_COUNT_MASK 0xFFFFFFFFu

#define DDA_AXIS_ENC_TIME 0x20u /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_TIME_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_TIME)
#define DDA_AXIS_ENC_TIME_RESET 0x00000000u
#define DDA_AXIS_ENC_TIME_CLOCKS_SHIFT 0u
#define DDA_AXIS_ENC_TIME_CLOCKS_MASK 0xFFFFFFFFu

#define DDA_AXIS_ENC_SCALE 0x24u /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_SCALE_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_SCALE)
#define DDA_AXIS_ENC_SCALE_RESET 0x00000000u
#define DDA_AXIS_ENC_SCALE_SCALE_SHIFT 0u
#define DDA_AXIS_ENC_SCALE_SCALE_MASK 0xFFFFFFFFu
#define DDA_AXIS_ENC_SCALE_MIN (0)
#define DDA_AXIS_ENC_SCALE_MAX (4294967295)

#define DDA_AXIS_FERROR_LIMIT 0x28u /* inside the block; a build with encoders only */
#define DDA_AXIS_FERROR_LIMIT_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_FERROR_LIMIT)
#define DDA_AXIS_FERROR_LIMIT_RESET 0x00000000u
#define DDA_AXIS_FERROR_LIMIT_COUNTS_SHIFT 0u
#define DDA_AXIS_FERROR_LIMIT_COUNTS_MASK 0xFFFFFFFFu
#define DDA_AXIS_FERROR_LIMIT_MIN (0)
#define DDA_AXIS_FERROR_LIMIT_MAX (4294967295)

#define DDA_AXIS_ENC_FERROR 0x2Cu /* inside the block; a build with encoders only */
#define DDA_AXIS_ENC_FERROR_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_ENC_FERROR)
#define DDA_AXIS_ENC_FERROR_RESET 0x00000000u
#define DDA_AXIS_ENC_FERROR_COUNTS_SHIFT 0u
#define DDA_AXIS_ENC_FERROR_COUNTS_MASK 0xFFFFFFFFu

#define DDA_AXIS_PROBE_ENC 0x30u /* inside the block; a build with encoders only */
#define DDA_AXIS_PROBE_ENC_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_PROBE_ENC)
#define DDA_AXIS_PROBE_ENC_RESET 0x00000000u
#define DDA_AXIS_PROBE_ENC_COUNT_SHIFT 0u
#define DDA_AXIS_PROBE_ENC_COUNT_MASK 0xFFFFFFFFu

#define DDA_AXIS_PROBE_POS 0x34u /* inside the block; a build with encoders only */
#define DDA_AXIS_PROBE_POS_OFFSET(axis) (DDA_AXIS_BLOCK(axis) + DDA_AXIS_PROBE_POS)
#define DDA_AXIS_PROBE_POS_RESET 0x00000000u
#define DDA_AXIS_PROBE_POS_STEPS_SHIFT 0u
#define DDA_AXIS_PROBE_POS_STEPS_MASK 0xFFFFFFFFu

#define DDA_PCI_VENDOR_ID 0x1234u
#define DDA_PCI_DEVICE_ID 0xDDA0u
#define DDA_PCI_REVISION_ID 0x01u
#define DDA_PCI_CLASS_CODE 0x088000u
#define DDA_PCI_SUBSYSTEM_VENDOR_ID 0x1234u
#define DDA_PCI_SUBSYSTEM_ID 0x0001u
#define DDA_BAR0_SIZE 256u /* I/O: function registers */
#define DDA_BAR1_SIZE 4096u /* memory: the command FIFO window */
#define DDA_BAR2_SIZE 4096u /* memory: the function registers at BAR0's offsets, then the per-axis blocks */
#define DDA_FIFO_DEPTH 512u /* words */

#define DDA_STOP_ESTOP 1u /* STOP_REASON.REASON */
#define DDA_STOP_WATCHDOG 2u /* STOP_REASON.REASON */
#define DDA_STOP_LIMIT 3u /* STOP_REASON.REASON */
#define DDA_STOP_FOLLOWING_ERROR 4u /* STOP_REASON.REASON */

/* The simulated card's socket protocol (sim/card/card_server.py) */
#define DDA_SIM_READ 1u /* a = register offset: BAR0's, or beyond it BAR2's per-axis blocks; answer: the register */
#define DDA_SIM_WRITE 2u /* a = register offset as READ's, b = value; answer: 0 */
#define DDA_SIM_FIFO 3u /* a = word count, then the words (one burst into BAR1); answer: 0 */
#define DDA_SIM_ADVANCE 4u /* a = card clocks; answer: card clocks since the server opened the card, low 32 bits */
#define DDA_SIM_REQUEST_WORDS 3u
#define DDA_SIM_ANSWER_WORDS 2u
#define DDA_SIM_MAX_BURST 4096u /* words in one FIFO request */
#define DDA_AXES_MAX 6u /* axis index i: X Y Z A B C */
#define DDA_AXIS_X 0u
#define DDA_AXIS_Y 1u
#define DDA_AXIS_Z 2u
#define DDA_AXIS_A 3u
#define DDA_AXIS_B 4u
#define DDA_AXIS_C 5u
#define DDA_OPCODE_SHIFT 28u
#define DDA_CMD_MAX_WORDS 10u /* the longest command of the N-axis form */
#define DDA_CMD_LINE 0x1u
#define DDA_CMD_LINE_OPERANDS 2u
#define DDA_CMD_LINE_WORDS 3u
#define DDA_CMD_LINE_MAX_WORDS 7u
#define DDA_CMD_LINE_BLEND_SHIFT 16u
#define DDA_CMD_LINE_BLEND_MASK 0x00010000u
#define DDA_CMD_LINE_AXES_SHIFT 20u
#define DDA_CMD_LINE_AXES_MASK 0x03F00000u
#define DDA_CMD_ARC 0x2u
#define DDA_CMD_ARC_OPERANDS 4u
#define DDA_CMD_ARC_WORDS 5u
#define DDA_CMD_ARC_MAX_WORDS 10u
#define DDA_CMD_ARC_CCW_SHIFT 0u
#define DDA_CMD_ARC_CCW_MASK 0x00000001u
#define DDA_CMD_ARC_VARIANT_SHIFT 1u
#define DDA_CMD_ARC_VARIANT_MASK 0x00000006u
#define DDA_CMD_ARC_LAMBDA_SHIFT 3u
#define DDA_CMD_ARC_LAMBDA_MASK 0x000000F8u
#define DDA_CMD_ARC_ACC_BITS_SHIFT 8u
#define DDA_CMD_ARC_ACC_BITS_MASK 0x00001F00u
#define DDA_CMD_ARC_BLEND_SHIFT 16u
#define DDA_CMD_ARC_BLEND_MASK 0x00010000u
#define DDA_CMD_ARC_U_AXIS_SHIFT 13u
#define DDA_CMD_ARC_U_AXIS_MASK 0x0000E000u
#define DDA_CMD_ARC_V_AXIS_SHIFT 17u
#define DDA_CMD_ARC_V_AXIS_MASK 0x000E0000u
#define DDA_CMD_ARC_HELIX_SHIFT 20u
#define DDA_CMD_ARC_HELIX_MASK 0x03F00000u
#define DDA_CMD_PULSE 0x3u
#define DDA_CMD_PULSE_OPERANDS 2u
#define DDA_CMD_PULSE_WORDS 3u
#define DDA_CMD_PULSE_MAX_WORDS 7u
#define DDA_CMD_PULSE_AXES_SHIFT 20u
#define DDA_CMD_PULSE_AXES_MASK 0x03F00000u
#define DDA_CMD_SET 0x4u
#define DDA_CMD_SET_OPERANDS 1u
#define DDA_CMD_SET_WORDS 2u
#define DDA_CMD_SET_INDEX_SHIFT 0u
#define DDA_CMD_SET_INDEX_MASK 0x0000000Fu
#define DDA_CMD_DWELL 0x5u
#define DDA_CMD_DWELL_OPERANDS 1u
#define DDA_CMD_DWELL_WORDS 2u
#define DDA_CMD_MARK 0x6u
#define DDA_CMD_MARK_OPERANDS 0u
#define DDA_CMD_MARK_WORDS 1u
#define DDA_CMD_MARK_TAG_SHIFT 0u
#define DDA_CMD_MARK_TAG_MASK 0x0000FFFFu
#define DDA_ERROR_NONE 0u
#define DDA_ERROR_BAD_OPCODE 1u
#define DDA_ERROR_RESERVED_BITS 2u
#define DDA_ERROR_RANGE 3u
#define DDA_ERROR_DDA_REJECTED 4u

#include <stdint.h>

/* Command builders: each writes a command's words (header, then operands) into
 * words[] and returns how many; it returns 0 and writes nothing when a header
 * field does not fit its width.  Signed operands are steps (two's complement). */

/* LINE: straight move by (DX, DY) steps (signed, must fit the coordinate width); N-axis form: by one displacement per axis in AXES, all axes ending together (docs/axes.md). */
static inline unsigned dda_cmd_line(uint32_t words[DDA_CMD_LINE_WORDS],
    int32_t dx,
    int32_t dy,
    uint32_t blend)
{
    if (blend > 0x1u)
        return 0u;
    words[0] = (DDA_CMD_LINE << DDA_OPCODE_SHIFT) | (blend << DDA_CMD_LINE_BLEND_SHIFT);
    words[1] = (uint32_t)dx;
    words[2] = (uint32_t)dy;
    return DDA_CMD_LINE_WORDS;
}

/* ARC: arc about the centre from (XS, YS) to (XE, YE), centre-relative signed steps; N-axis form: in the plane (U_AXIS, V_AXIS), XS .. YE its (u, v) coordinates, the HELIX axes moving linearly with the arc's ITERATIONS (docs/axes.md). */
static inline unsigned dda_cmd_arc(uint32_t words[DDA_CMD_ARC_WORDS],
    int32_t xs,
    int32_t ys,
    int32_t xe,
    int32_t ye,
    uint32_t ccw,
    uint32_t variant,
    uint32_t lambda,
    uint32_t acc_bits,
    uint32_t blend)
{
    if (ccw > 0x1u || variant > 0x3u || lambda > 0x1Fu || acc_bits > 0x1Fu || blend > 0x1u)
        return 0u;
    words[0] = (DDA_CMD_ARC << DDA_OPCODE_SHIFT) | (ccw << DDA_CMD_ARC_CCW_SHIFT) | (variant << DDA_CMD_ARC_VARIANT_SHIFT) | (lambda << DDA_CMD_ARC_LAMBDA_SHIFT) | (acc_bits << DDA_CMD_ARC_ACC_BITS_SHIFT) | (blend << DDA_CMD_ARC_BLEND_SHIFT);
    words[1] = (uint32_t)xs;
    words[2] = (uint32_t)ys;
    words[3] = (uint32_t)xe;
    words[4] = (uint32_t)ye;
    return DDA_CMD_ARC_WORDS;
}

/* PULSE: direct pulses: signed counts per axis at PULSE_PERIOD_X / _Y, both axes at once; N-axis form: one count per axis in AXES, at that axis's PULSE_PERIOD. */
static inline unsigned dda_cmd_pulse(uint32_t words[DDA_CMD_PULSE_WORDS],
    int32_t count_x,
    int32_t count_y)
{
    words[0] = (DDA_CMD_PULSE << DDA_OPCODE_SHIFT);
    words[1] = (uint32_t)count_x;
    words[2] = (uint32_t)count_y;
    return DDA_CMD_PULSE_WORDS;
}

/* SET: write VALUE into a register at this point of the stream (clamped like a bus write). */
static inline unsigned dda_cmd_set(uint32_t words[DDA_CMD_SET_WORDS],
    uint32_t value,
    uint32_t index)
{
    if (index > 0xFu)
        return 0u;
    words[0] = (DDA_CMD_SET << DDA_OPCODE_SHIFT) | (index << DDA_CMD_SET_INDEX_SHIFT);
    words[1] = (uint32_t)value;
    return DDA_CMD_SET_WORDS;
}

/* DWELL: wait CLOCKS clocks (32-bit) before the next command. */
static inline unsigned dda_cmd_dwell(uint32_t words[DDA_CMD_DWELL_WORDS],
    uint32_t clocks)
{
    words[0] = (DDA_CMD_DWELL << DDA_OPCODE_SHIFT);
    words[1] = (uint32_t)clocks;
    return DDA_CMD_DWELL_WORDS;
}

/* MARK: set INT_STATUS.MARK and MARK_TAG when reached. */
static inline unsigned dda_cmd_mark(uint32_t words[DDA_CMD_MARK_WORDS],
    uint32_t tag)
{
    if (tag > 0xFFFFu)
        return 0u;
    words[0] = (DDA_CMD_MARK << DDA_OPCODE_SHIFT) | (tag << DDA_CMD_MARK_TAG_SHIFT);
    return DDA_CMD_MARK_WORDS;
}

/* LINE, N-axis form (docs/axes.md): d[i] is axis i's operand, read for the axes
 * in AXES only (AXES = 0: X, Y). */
static inline unsigned dda_cmd_line_axes(uint32_t words[DDA_CMD_LINE_MAX_WORDS],
    uint32_t axes,
    const int32_t d[DDA_AXES_MAX],
    uint32_t blend)
{
    uint32_t chosen = axes ? axes : 0x3u;
    unsigned length = 1u;
    if (axes > 0x3Fu || blend > 0x1u)
        return 0u;
    words[0] = (DDA_CMD_LINE << DDA_OPCODE_SHIFT) | (axes << DDA_CMD_LINE_AXES_SHIFT) | (blend << DDA_CMD_LINE_BLEND_SHIFT);
    for (unsigned axis = 0u; axis < DDA_AXES_MAX; axis++)
        if ((chosen >> axis) & 1u)
            words[length++] = (uint32_t)d[axis];
    return length;
}

/* ARC, N-axis form (docs/axes.md): d[i] is axis i's operand, read for the axes
 * in HELIX only (HELIX = 0: no axis operands). */
static inline unsigned dda_cmd_arc_helix(uint32_t words[DDA_CMD_ARC_MAX_WORDS],
    int32_t xs,
    int32_t ys,
    int32_t xe,
    int32_t ye,
    uint32_t iterations,
    uint32_t helix,
    const int32_t d[DDA_AXES_MAX],
    uint32_t ccw,
    uint32_t variant,
    uint32_t lambda,
    uint32_t acc_bits,
    uint32_t blend,
    uint32_t u_axis,
    uint32_t v_axis)
{
    unsigned length = 1u;
    if (helix > 0x3Fu || ccw > 0x1u || variant > 0x3u || lambda > 0x1Fu || acc_bits > 0x1Fu || blend > 0x1u || u_axis > 0x7u || v_axis > 0x7u)
        return 0u;
    words[0] = (DDA_CMD_ARC << DDA_OPCODE_SHIFT) | (helix << DDA_CMD_ARC_HELIX_SHIFT) | (ccw << DDA_CMD_ARC_CCW_SHIFT) | (variant << DDA_CMD_ARC_VARIANT_SHIFT) | (lambda << DDA_CMD_ARC_LAMBDA_SHIFT) | (acc_bits << DDA_CMD_ARC_ACC_BITS_SHIFT) | (blend << DDA_CMD_ARC_BLEND_SHIFT) | (u_axis << DDA_CMD_ARC_U_AXIS_SHIFT) | (v_axis << DDA_CMD_ARC_V_AXIS_SHIFT);
    words[length++] = (uint32_t)xs;
    words[length++] = (uint32_t)ys;
    words[length++] = (uint32_t)xe;
    words[length++] = (uint32_t)ye;
    if (helix != 0u) {
        words[length++] = (uint32_t)iterations;
    }
    for (unsigned axis = 0u; axis < DDA_AXES_MAX; axis++)
        if ((helix >> axis) & 1u)
            words[length++] = (uint32_t)d[axis];
    return length;
}

/* PULSE, N-axis form (docs/axes.md): count[i] is axis i's operand, read for the axes
 * in AXES only (AXES = 0: X, Y). */
static inline unsigned dda_cmd_pulse_axes(uint32_t words[DDA_CMD_PULSE_MAX_WORDS],
    uint32_t axes,
    const int32_t count[DDA_AXES_MAX])
{
    uint32_t chosen = axes ? axes : 0x3u;
    unsigned length = 1u;
    if (axes > 0x3Fu)
        return 0u;
    words[0] = (DDA_CMD_PULSE << DDA_OPCODE_SHIFT) | (axes << DDA_CMD_PULSE_AXES_SHIFT);
    for (unsigned axis = 0u; axis < DDA_AXES_MAX; axis++)
        if ((chosen >> axis) & 1u)
            words[length++] = (uint32_t)count[axis];
    return length;
}

#endif /* DDA_REGISTERS_H */
