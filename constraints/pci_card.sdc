# Timing constraints of the PCI DDA card for vendor flows (SDC).
# Port names are those of gen/top.v.  The open flow (fpgaflow) does not
# read this file: nextpnr-ice40 takes its 33 MHz target from --freq, and the
# script checks the PCI pin budgets itself.

# PCI 33: 33.33 MHz, 30 ns period.
create_clock -name pci_clk -period 30.000 [get_ports clock]

# Lines the card samples.  The driving agent's output is valid at most 11 ns
# after CLK and the bus leaves 7 ns of set-up: input delay 30 - 7 = 23 ns.
# PCI input hold is 0 ns: a line may change right at the clock edge.
set_input_delay -clock pci_clk -max 23.000 [get_ports {pci_pins_ad[*] pci_pins_cbe[*] pci_pins_par pci_pins_frame pci_pins_irdy pci_pins_idsel}]
set_input_delay -clock pci_clk -min 0.000 [get_ports {pci_pins_ad[*] pci_pins_cbe[*] pci_pins_par pci_pins_frame pci_pins_irdy pci_pins_idsel}]

# Lines the card drives: valid 2 ns to 11 ns after CLK.
# Output delay max 30 - 11 = 19 ns; the -2 ns minimum output delay makes the
# hold check demand at least 2 ns from CLK to a changing output.
set_output_delay -clock pci_clk -max 19.000 [get_ports {pci_pins_ad[*] pci_pins_par pci_pins_trdy pci_pins_devsel pci_pins_stop pci_pins_perr pci_pins_serr pci_pins_inta}]
set_output_delay -clock pci_clk -min -2.000 [get_ports {pci_pins_ad[*] pci_pins_par pci_pins_trdy pci_pins_devsel pci_pins_stop pci_pins_perr pci_pins_serr pci_pins_inta}]

# RST# is asynchronous (asserted and released with CLK running but no timing
# relation); STEP/DIR and DRIVE_ENABLE drive motor power stages micro-seconds
# apart; the machine inputs are asynchronous switches, each through a
# two-flip-flop synchroniser.
set_false_path -from [get_ports reset]
set_false_path -to [get_ports {motor_step_x motor_dir_x motor_step_y motor_dir_y motor_drive_enable}]
set_false_path -from [get_ports {motor_estop motor_limit_* motor_home_*}]
