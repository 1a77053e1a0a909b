// channels.hpp — LCM channel names of a SIL run (spec 00 §5.1). One place, so the nodes, the
// logger and tools/sil agree.
#ifndef HIL_SIL_CHANNELS_HPP
#define HIL_SIL_CHANNELS_HPP

namespace sil {

constexpr const char *kChSensor = "GNC_SENSOR";   // sensor_frame_v2_t   plant  -> bridge
constexpr const char *kChCmd = "GNC_CMD";         // actuator_cmd_v2_t   bridge -> plant
constexpr const char *kChTlm = "GNC_TLM";         // fsw_tlm_frame_t  bridge -> logger
constexpr const char *kChTruth = "GNC_TRUTH";     // sim_truth_t      plant  -> logger
constexpr const char *kChCtl = "GNC_CTL";         // sil_ctl_t        runner <-> nodes
constexpr const char *kChTblUp = "GNC_TBL_UP";    // table_upload_v2_t   tools  -> bridge
constexpr const char *kChTblAck = "GNC_TBL_ACK";  // table_ack_t      bridge -> tools
constexpr const char *kChFswCmd = "GNC_FSW_CMD";  // fsw_cmd_v2_t        ground -> bridge

}  // namespace sil

#endif  // HIL_SIL_CHANNELS_HPP
