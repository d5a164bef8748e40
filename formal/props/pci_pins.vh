// The PCI pins of the unit under proof (gen/pci_slave.v, gen/card.v), its
// clock and reset: the port connections pci_target_harness.sv and
// card_harness.sv share, included inside the unit's instance (the lines
// of pci_bus_lines.vh).
        .clock(clock), .reset(reset_n),
        .pci_ad_in(ad), .pci_ad_out(t_ad), .pci_ad_oe(t_ad_oe), .pci_cbe_in(m_cbe_n),
        .pci_par_in(par), .pci_par_out(t_par), .pci_par_oe(t_par_oe),
        .pci_frame_in(m_frame_n), .pci_irdy_in(m_irdy_n), .pci_idsel_in(m_idsel),
        .pci_trdy_out(t_trdy_n), .pci_trdy_oe(t_trdy_oe), .pci_devsel_out(t_devsel_n),
        .pci_devsel_oe(t_devsel_oe), .pci_stop_out(t_stop_n), .pci_stop_oe(t_stop_oe),
        .pci_perr_out(t_perr_n), .pci_perr_oe(t_perr_oe), .pci_serr_out(t_serr_n),
        .pci_serr_oe(t_serr_oe), .pci_inta_out(t_inta_n), .pci_inta_oe(t_inta_oe)
