// The PCI lines of a harness with one target under proof (included by
// pci_target_harness.sv and card_harness.sv before the unit): the target's
// drivers, and each shared line as the bus carries it, the target's driver
// where it drives, else the initiator's (m_*), the other targets' (o_*,
// 1 in a harness with no other target) wired-AND on TRDY#, DEVSEL#, STOP#.
    wire [31:0] t_ad;
    wire t_ad_oe, t_par, t_par_oe, t_trdy_n, t_trdy_oe, t_devsel_n, t_devsel_oe;
    wire t_stop_n, t_stop_oe, t_perr_n, t_perr_oe, t_serr_n, t_serr_oe, t_inta_n, t_inta_oe;

    wire [31:0] ad = t_ad_oe ? t_ad : m_ad;
    wire par = t_par_oe ? t_par : m_par;
    wire trdy_n = (t_trdy_oe ? t_trdy_n : 1'b1) & o_trdy_n;
    wire devsel_n = (t_devsel_oe ? t_devsel_n : 1'b1) & o_devsel_n;
    wire stop_n = (t_stop_oe ? t_stop_n : 1'b1) & o_stop_n;
    wire perr_n = t_perr_oe ? t_perr_n : 1'b1;
    wire serr_n = t_serr_oe ? t_serr_n : 1'b1;
